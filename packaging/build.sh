#!/usr/bin/env bash
# Build the one-folder desktop bundle into build/dist/lightinv and run its self-test.
#   ./packaging/build.sh          (after ./dev.sh setup)
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x .venv/bin/python ] || ./dev.sh setup
.venv/bin/python -m pip install -q 'pyinstaller>=6,<7'
.venv/bin/pyinstaller --noconfirm --log-level WARN --distpath build/dist --workpath build/pyi \
  packaging/lightinv.spec
echo "bundle: build/dist/lightinv ($(du -sh build/dist/lightinv | cut -f1))"
build/dist/lightinv/lightinv --self-test
