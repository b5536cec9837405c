"""The low-rank radiosity operator: build to a target accuracy, evaluation, cache,
luminaire responses, a Dask cluster build.
"""
