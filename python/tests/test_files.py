"""The CLI's mesh files read by the tools that users open them with: meshio and VTK read the
.vtu in each encoding, the .neigh and .face files follow TetGen's layout and agree with the
binding, and --canonical makes runs comparable with diff."""
import filecmp
import os
import subprocess

import numpy as np
import pytest

import dtlab

CLI = os.environ.get("DTLAB_CLI")
pytestmark = pytest.mark.skipif(CLI is None, reason="DTLAB_CLI names the dtlab binary (ctest sets it)")


def dtlab_cli(*args):
    return subprocess.run([CLI, *map(str, args)], check=True, capture_output=True, text=True)


def read_table(path, columns):
    """A TetGen file's rows after its header line, comments skipped."""
    rows = [line.split() for line in open(path) if line.strip() and not line.startswith("#")]
    header, body = rows[0], rows[1:]
    assert int(header[0]) == len(body)
    return np.array([[int(v) for v in row[1:1 + columns]] for row in body]), header


@pytest.fixture(scope="module")
def sphere_mesh(tmp_path_factory):
    """sphere:3000 with the fast kernel: some non-Delaunay faces to flag in the cell array."""
    out = tmp_path_factory.mktemp("mesh")
    dtlab_cli("generate", "sphere", 3000, "--seed", 2, "-o", out / "points.xyz")
    run = subprocess.run([CLI, "triangulate", out / "points.xyz", "--predicates", "fast",
                          "--validate", "-o", out / "mesh.ele"], capture_output=True, text=True)
    assert run.returncode in (0, 1)
    tets, _ = read_table(out / "mesh.ele", 4)
    points = np.loadtxt(out / "points.xyz")
    return out, points, tets


def ascii_flags(out):
    """The non_delaunay cell array of the sphere mesh, from an ASCII .vtu, by plain text."""
    path = out / "flags-ascii.vtu"
    if not path.exists():
        subprocess.run([CLI, "triangulate", out / "points.xyz", "--predicates", "fast",
                        "--validate", "-o", path, "--vtu", "ascii"], capture_output=True)
    text = open(path).read()
    body = text.split('Name="non_delaunay" format="ascii">')[1].split("</DataArray>")[0]
    return np.array([int(v) for v in body.split()])


@pytest.mark.parametrize("encoding", ["zlib", "binary", "ascii"])
def test_vtu_is_read_by_meshio_and_vtk_with_its_cell_array(sphere_mesh, encoding):
    import meshio
    from vtk.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

    out, points, tets = sphere_mesh
    vtu = out / f"mesh-{encoding}.vtu"
    run = subprocess.run([CLI, "triangulate", out / "points.xyz", "--predicates", "fast",
                          "--validate", "-o", vtu, "--vtu", encoding], capture_output=True, text=True)
    assert run.returncode in (0, 1)
    text = open(vtu, "rb").read()
    assert (b'format="ascii"' in text) == (encoding == "ascii")
    assert (b"vtkZLibDataCompressor" in text) == (encoding == "zlib")

    mesh = meshio.read(vtu)
    assert np.array_equal(mesh.points, points)
    assert np.array_equal(mesh.cells_dict["tetra"], tets)
    flags = mesh.cell_data["non_delaunay"][0]
    # The flags as written in text, decoded without base64 or zlib: the binary encodings must
    # carry the same values, and the fast kernel's mesh must have some to carry.
    assert np.array_equal(flags, ascii_flags(out))
    assert flags.sum() > 0

    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(vtu))
    reader.Update()
    grid = reader.GetOutput()
    assert grid.GetNumberOfPoints() == len(points) and grid.GetNumberOfCells() == len(tets)
    assert np.array_equal(vtk_to_numpy(grid.GetPoints().GetData()), points)
    connectivity = vtk_to_numpy(grid.GetCells().GetConnectivityArray())
    assert np.array_equal(connectivity.reshape(-1, 4), tets)
    assert np.array_equal(vtk_to_numpy(grid.GetCellData().GetArray("non_delaunay")), flags)
    assert set(vtk_to_numpy(grid.GetCellTypesArray())) == {10}


def test_binary_vtu_is_smaller_than_ascii_and_zlib_smaller_still(sphere_mesh):
    out, _, _ = sphere_mesh
    sizes = {}
    for encoding in ["zlib", "binary", "ascii"]:
        path = out / f"size-{encoding}.vtu"
        dtlab_cli("triangulate", out / "points.xyz", "-o", path, "--vtu", encoding)
        sizes[encoding] = os.path.getsize(path)
    assert sizes["zlib"] < sizes["binary"] < sizes["ascii"]


def test_neigh_and_face_files_agree_with_the_binding(tmp_path):
    points = dtlab.generate("uniform", 2000, seed=4)
    np.savetxt(tmp_path / "p.xyz", points, fmt="%.17g")
    dtlab_cli("triangulate", tmp_path / "p.xyz", "-o", tmp_path / "m.ele", "--neighbors", "--hull")
    tets, _ = read_table(tmp_path / "m.ele", 4)
    neighbors, header = read_table(tmp_path / "m.neigh", 4)
    assert header[1] == "4"
    faces, header = read_table(tmp_path / "m.face", 3)
    assert header[1] == "1"  # boundary markers follow
    # TetGen's -nn columns after the marker: the tetrahedron inside, -1 outside
    behind, _ = read_table(tmp_path / "m.face", 6)
    assert (behind[:, 3] == 1).all() and (behind[:, 5] == -1).all()
    tri = dtlab.triangulate(points)
    assert np.array_equal(tets, tri.simplices)
    assert np.array_equal(neighbors, tri.neighbors)
    assert np.array_equal(faces, tri.convex_hull)
    for f in range(0, len(faces), 13):
        assert set(faces[f]) < set(tets[behind[f, 4]])
    # TetGen's convention: neighbour i is across the face opposite vertex i.
    for t in range(0, len(tets), 97):
        for i in range(4):
            n = neighbors[t][i]
            if n >= 0:
                shared = set(tets[t]) - {tets[t][i]}
                assert shared <= set(tets[n])


def test_canonical_output_compares_with_diff_across_methods_and_threads(tmp_path):
    runs = [("a.ele", []), ("b.ele", ["--method", "optimistic-detect", "--threads", "2"]),
            ("c.ele", ["--paper"]),
            ("d.ele", ["--method", "partitioned", "--threads", "2", "--insertion", "flips"])]
    np.savetxt(tmp_path / "p.xyz", dtlab.generate("uniform", 5000), fmt="%.17g")
    runs.append(("e.ele", ["--seed", "9"]))  # another insertion order of the same points
    for name, options in runs:
        dtlab_cli("triangulate", tmp_path / "p.xyz", "--canonical", "-o", tmp_path / name, *options)
    for name, _ in runs[1:]:
        assert filecmp.cmp(tmp_path / "a.ele", tmp_path / name, shallow=False), name
    # without --canonical the files differ (the order depends on the run)
    dtlab_cli("triangulate", tmp_path / "p.xyz", "-o", tmp_path / "plain.ele", "--paper")
    assert not filecmp.cmp(tmp_path / "a.ele", tmp_path / "plain.ele", shallow=False)


def test_validate_any_orientation_accepts_qhulls_lists(tmp_path):
    from scipy.spatial import Delaunay
    points = dtlab.generate("uniform", 1000, seed=6)
    np.savetxt(tmp_path / "p.xyz", points, fmt="%.17g")
    with open(tmp_path / "qhull.ele", "w") as f:
        simplices = Delaunay(points).simplices
        f.write(f"{len(simplices)} 4 0\n")
        for i, t in enumerate(simplices):
            f.write(f"{i} {t[0]} {t[1]} {t[2]} {t[3]}\n")
    strict = subprocess.run([CLI, "validate", tmp_path / "p.xyz", tmp_path / "qhull.ele"],
                            capture_output=True, text=True)
    assert strict.returncode == 1 and '"non_positive_orientation": 0' not in strict.stdout
    loose = subprocess.run([CLI, "validate", tmp_path / "p.xyz", tmp_path / "qhull.ele",
                            "--any-orientation"], capture_output=True, text=True)
    assert loose.returncode == 0 and '"turned_tetrahedra"' in loose.stdout
