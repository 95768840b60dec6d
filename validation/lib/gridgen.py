"""Write an analytic flow field as a foam2grid-format .vti (docs/grid-format.md) with VTK."""
import numpy as np
import vtk
from vtk.util import numpy_support as ns


def write_vti(path, origin, spacing, shape, U, k, eps, nu, valid=None):
    """U: (nx, ny, nz, 3), k, eps: (nx, ny, nz) arrays in SI; x fastest in the file."""
    nx, ny, nz = shape
    img = vtk.vtkImageData()
    img.SetOrigin(*origin)
    img.SetSpacing(*spacing)
    img.SetDimensions(nx, ny, nz)

    def flat(a, nc=1):
        a = np.asarray(a)
        if nc == 1:
            return np.ascontiguousarray(a.transpose(2, 1, 0).reshape(-1))
        return np.ascontiguousarray(a.transpose(2, 1, 0, 3).reshape(-1, nc))
    cmu = 0.09
    nut = cmu * np.asarray(k) ** 2 / np.asarray(eps)
    if valid is None:
        valid = np.ones(shape, np.uint8)
    for name, arr, nc in (("U", U, 3), ("k", k, 1), ("epsilon", eps, 1), ("nut", nut, 1)):
        a = flat(np.asarray(arr, np.float32) * (valid[..., None] if nc == 3 else valid), nc)
        va = ns.numpy_to_vtk(a.astype(np.float32), deep=True)
        va.SetName(name)
        img.GetPointData().AddArray(va)
    vv = ns.numpy_to_vtk(flat(valid.astype(np.uint8)), deep=True,
                         array_type=vtk.VTK_UNSIGNED_CHAR)
    vv.SetName("valid")
    img.GetPointData().AddArray(vv)
    fd = vtk.vtkDoubleArray()
    fd.SetName("kinematic_viscosity")
    fd.InsertNextValue(nu)
    img.GetFieldData().AddArray(fd)
    tm = vtk.vtkDoubleArray()
    tm.SetName("time")
    tm.InsertNextValue(0.0)
    img.GetFieldData().AddArray(tm)
    w = vtk.vtkXMLImageDataWriter()
    w.SetFileName(path)
    w.SetInputData(img)
    w.SetDataModeToAppended()
    w.EncodeAppendedDataOff()
    w.SetHeaderTypeToUInt64()
    w.SetCompressorTypeToZLib()
    if not w.Write():
        raise RuntimeError("cannot write " + path)
