"""Helpers of the export tests (tests/core/test_export_*.py): a small solved office."""
