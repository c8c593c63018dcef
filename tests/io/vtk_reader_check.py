"""Reads a run's VTK snapshots with VTK's own readers and checks what ParaView would see.

Usage: vtk_reader_check.py PERIFLEX SCENE OUT_DIR
Runs `PERIFLEX run SCENE --vtk-every 50 --until 0.02`, then opens vtk/snapshots.pvd's files with
vtkXMLUnstructuredGridReader / vtkXMLPolyDataReader and checks: positions and displacements are
Float64; displacement = position - (first snapshot's position) for particles that start on their
reference grid; volume and body arrays present; rigid bodies are polygons; the .pvd lists both
parts at every time. Exits 77 (skip) when the vtk module is not installed (python3-vtk9).
"""
import os
import re
import subprocess
import sys

try:
    import vtk
except ImportError:
    print("python3-vtk9 is not installed: the check with VTK's reader is skipped")
    sys.exit(77)

periflex, scene, out = sys.argv[1:4]
subprocess.run([periflex, "run", scene, "--out", out, "--vtk-every", "50", "--until", "0.02"],
               check=True, stdout=subprocess.DEVNULL)
vtk_dir = os.path.join(out, "vtk")
pvd = open(os.path.join(vtk_dir, "snapshots.pvd")).read()
entries = re.findall(r'timestep="([^"]+)" part="(\d)" file="([^"]+)"', pvd)
times = sorted({float(t) for t, _, _ in entries})
assert len(times) == 17, f"expected 17 snapshot times (800 steps / 50 + 1), found {len(times)}"
for t in times:
    parts = {p for tt, p, _ in entries if float(tt) == t}
    assert parts == {"0", "1"}, f"t = {t}: parts {parts}"

first_positions = None
for t, part, name in entries:
    path = os.path.join(vtk_dir, name)
    if part == "0":
        reader = vtk.vtkXMLUnstructuredGridReader()
        reader.SetFileName(path)
        reader.Update()
        grid = reader.GetOutput()
        n = grid.GetNumberOfPoints()
        assert n > 0 and grid.GetNumberOfCells() == n, f"{name}: {n} points"
        assert grid.GetPoints().GetDataType() == vtk.VTK_DOUBLE, f"{name}: positions not Float64"
        data = grid.GetPointData()
        for array in ("displacement", "velocity", "damage", "strain", "volume", "body", "speed"):
            assert data.GetArray(array) is not None, f"{name}: no array {array}"
        u = data.GetArray("displacement")
        assert u.GetDataType() == vtk.VTK_DOUBLE and u.GetNumberOfComponents() == 3
        assert data.GetVectors().GetName() == "displacement", "Warp By Vector needs displacement as the vectors"
        points = grid.GetPoints()
        positions = [points.GetPoint(i) for i in range(n)]
        volume = data.GetArray("volume")
        assert all(volume.GetValue(i) > 0 for i in range(n)), f"{name}: a particle without volume"
        if first_positions is None:
            first_positions = positions
        else:
            # displacement is measured from the reference grid, which the first snapshot holds
            # (up to the initial projection, far below these motions)
            err = max(abs(positions[i][k] - u.GetTuple3(i)[k] - first_positions[i][k])
                      for i in range(n) for k in range(2))
            assert err < 1e-9, f"{name}: position - displacement is {err} from the reference"
    else:
        reader = vtk.vtkXMLPolyDataReader()
        reader.SetFileName(path)
        reader.Update()
        poly = reader.GetOutput()
        assert poly.GetNumberOfPolys() >= 1, f"{name}: no polygon"
        assert poly.GetCellData().GetArray("body") is not None
        assert poly.GetCellData().GetArray("angle") is not None
print(f"read {len(entries)} files at {len(times)} times with VTK {vtk.vtkVersion.GetVTKVersion()}")
