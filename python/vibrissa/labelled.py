"""Labelled results: xarray Datasets with named dimensions, coordinates, units and descriptions.

The variables come from the same C++ table as the HDF5 file of the result (io/labelled_data.hpp), so
``result.to_xarray()`` is what ``xarray.open_dataset(file)`` gives for the file the result writes
(``array.h5``, ``frames.h5``; the ``render`` group of ``array.h5`` with ``group="render"``). Needs
python3-xarray. See docs/python.md, "Labelled results".
"""

__all__ = ["to_dataset"]


def to_dataset(description, group=""):
    """An ``xarray.Dataset`` of one group of a labelled description (the ``labelled()`` of a C++ result:
    ``{"variables": [(path, dims, attrs, values)], "attributes": [(group, name, value)]}``). A variable whose
    only dimension carries its name is that dimension's coordinate."""
    import xarray as xr

    groups = {path.rpartition("/")[0] for path, *_ in description["variables"]}
    if group not in groups:
        raise ValueError(f"group must be one of {sorted(groups)}, got {group!r}")
    coords, data_vars = {}, {}
    for path, dims, attrs, values in description["variables"]:
        where, _, name = path.rpartition("/")
        if where != group:
            continue
        if values.dtype.kind == "U":  # as netCDF-4 readers return strings
            values = values.astype(object)
        variable = xr.Variable(dims, values, attrs=dict(attrs))
        if tuple(dims) == (name,):
            coords[name] = variable
        else:
            data_vars[name] = variable
    attributes = {name: value for where, name, value in description["attributes"] if where == group}
    return xr.Dataset(data_vars, coords=coords, attrs=attributes)
