"""The Python module: label arrays and files in, numpy arrays and files out, options named as
on the command line, errors as Python exceptions, the GIL released and Ctrl-C honoured.
Run by ctest (test 'python') with PYTHONPATH=<build>/python."""
import _thread
import importlib.util
import os
import threading
import time

import numpy as np
import pytest

import voronoimesh as vm


def two_blocks(n=16, dtype=np.int32, order="F"):
    """Labels indexed [x, y, z]: a block of 3 (x < 8) beside a block of 7 (x >= 8) inside
    background 0."""
    labels = np.zeros((n, n, n), dtype=dtype, order=order)
    labels[3:8, 3:13, 3:13] = 3
    labels[8:13, 3:13, 3:13] = 7
    return labels


def closed_and_consistent(mesh):
    """Every phase's boundary closed: each edge is shared by an even number of its
    phase's triangles (counted over both sides)."""
    edges = {}
    for tri, pair in zip(mesh.triangles, mesh.phases):
        for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
            for phase in pair:
                key = (min(a, b), max(a, b), phase)
                edges[key] = edges.get(key, 0) + 1
    return all(count % 2 == 0 for count in edges.values())


def test_label_arrays_give_numpy_meshes_in_labels_and_world_units():
    mesh = vm.mesh_labels(two_blocks(), spacing=(0.5, 1, 2), origin=(10, 20, 30), iterations=5)
    assert mesh.points.dtype == np.float64 and mesh.points.shape[1] == 3
    assert mesh.triangles.dtype == np.int32 and mesh.triangles.shape == (mesh.num_triangles, 3)
    assert mesh.phases.dtype == np.int32 and mesh.phases.shape == (mesh.num_triangles, 2)
    assert mesh.phase_labels == [0, 3, 7]
    assert mesh.phase_names == ["background", "label3", "label7"]
    assert set(map(tuple, mesh.phases)) == {(0, 3), (0, 7), (3, 7)}
    assert not mesh.points.flags.writeable  # a view of the mesh, not a copy to edit
    assert mesh.validate() == [] and closed_and_consistent(mesh)
    # [x, y, z] indexing: the 3|7 surface lies halfway between x indices 7 and 8.
    between = mesh.triangles[(mesh.phases[:, 0] == 3) & (mesh.phases[:, 1] == 7)]
    xs = mesh.points[between.ravel(), 0]
    assert np.allclose(xs, 10 + 0.5 * 7.5, atol=0.5 * 0.5)
    assert mesh.points[:, 2].min() > 30 and mesh.points[:, 2].max() < 30 + 2 * 15
    stats = mesh.stats()
    assert stats["triangles"] == mesh.num_triangles and stats["phases"] == 3 and stats["min_quality"] > 0.2
    worst = mesh.stats(worst=3)["worst_triangles"]
    assert len(worst) == 3 and worst[0]["quality"] == stats["min_quality"] and "worst_triangles" not in stats
    assert len(mesh.stats(folds=5).get("sharpest_folds", [])) == min(5, stats["folds"]) and "sharpest_folds" not in stats
    assert all(len(c["phases"]) >= 2 and set(c["phases"]) <= {0, 3, 7} for w in worst for c in w["corners"])
    curves = mesh.junctions()
    assert curves and all(c["phases"] == (0, 3, 7) for c in curves) and all(c["closed"] for c in curves)


def test_a_closed_meshs_voxel_centres_lie_in_their_labels_phases():
    labels = two_blocks()
    mesh = vm.mesh_labels(labels, spacing=(0.5, 1, 2), origin=(10, 20, 30), iterations=5, close=True)
    a = mesh.label_agreement(labels, spacing=(0.5, 1, 2), origin=(10, 20, 30))
    assert a["voxels"] == labels.size and a["undecided"] == 0  # the outer layer too, on the box faces
    assert [l["label"] for l in a["labels"]] == [0, 3, 7]
    assert sum(l["voxels"] for l in a["labels"]) == a["voxels"]
    assert a["interior_in_phase"] == a["interior"] > 0 and a["in_phase"] > 0.9 * a["voxels"]
    # Compared with other labels, the same mesh disagrees: the count can fail.
    swapped = np.where(labels == 3, 7, np.where(labels == 7, 3, labels))
    assert mesh.label_agreement(swapped, spacing=(0.5, 1, 2), origin=(10, 20, 30))["in_phase"] < a["in_phase"]
    with pytest.raises(ValueError, match="not closed"):
        vm.mesh_labels(labels, iterations=1).label_agreement(labels)
    reals = labels.astype(np.float64)  # as nibabel's get_fdata() gives them: the same labels
    assert mesh.label_agreement(reals, spacing=(0.5, 1, 2), origin=(10, 20, 30)) == a
    reals[0, 0, 0] = 0.5
    with pytest.raises(ValueError, match=r"labels\[0, 0, 0\] is 0.5, not a label"):
        mesh.label_agreement(reals)


def test_any_integer_array_and_order_gives_the_same_mesh():
    reference = vm.mesh_labels(two_blocks(), iterations=2)
    for dtype, order in [(np.uint8, "C"), (np.int64, "F"), (np.int16, "C")]:
        other = vm.mesh_labels(two_blocks(dtype=dtype, order=order), iterations=2)
        assert np.array_equal(other.points, reference.points) and np.array_equal(other.triangles, reference.triangles)


def test_reals_that_are_whole_numbers_and_masks_are_labels():
    # nibabel's get_fdata() gives float64 for any segmentation.
    reference = vm.mesh_labels(two_blocks(), iterations=2)
    for dtype in [np.float64, np.float32]:
        reals = vm.mesh_labels(two_blocks(dtype=dtype), iterations=2)
        assert np.array_equal(reals.points, reference.points) and np.array_equal(reals.triangles, reference.triangles)
    blurred = two_blocks(dtype=np.float64)
    blurred[3, 4, 5] = 2.5  # linear interpolation's work
    with pytest.raises(ValueError, match=r"labels\[3, 4, 5\] is 2.5, not a label"):
        vm.mesh_labels(blurred)
    blurred[3, 4, 5] = 2**31
    with pytest.raises(ValueError, match=r"is 2147483648.0, not a label"):
        vm.mesh_labels(blurred)
    mask = vm.mesh_labels(two_blocks() > 0, iterations=1)
    assert mask.phase_labels == [0, 1] and mask.validate() == []


def test_labels_beyond_32_bits_are_refused_not_cut_and_the_extremes_kept():
    # numpy's cast to int32 would make label 2**41 a 0 (a phase merged into another) without a word.
    wide = two_blocks(dtype=np.int64)
    wide[wide == 7] = 2**41
    with pytest.raises(ValueError, match="value 2199023255552 is not a 32-bit label"):
        vm.mesh_labels(wide, iterations=1)
    closed = vm.mesh_labels(two_blocks(), iterations=1, close=True)
    with pytest.raises(ValueError, match="value 2199023255552 is not a 32-bit label"):
        closed.label_agreement(wide.astype(np.uint64))
    wide[wide == 2**41] = -2**31
    wide[wide == 3] = 2**31 - 1
    assert vm.mesh_labels(wide, iterations=1).phase_labels == [-2**31, 0, 2**31 - 1]


def test_the_mesh_does_not_depend_on_the_thread_count():
    one = vm.mesh_labels(two_blocks(), iterations=4, threads=1)
    two = vm.mesh_labels(two_blocks(), iterations=4, threads=2)
    assert np.array_equal(one.points, two.points) and np.array_equal(one.triangles, two.triangles)


def test_options_are_the_command_lines_and_bad_ones_raise():
    mesh = vm.mesh_labels(two_blocks(), iterations=0, drop_labels=[7], close=True)
    assert mesh.phase_names == ["background", "label3", "exterior"]
    with pytest.raises(ValueError, match="iterations: must be 0 or more"):
        vm.mesh_labels(two_blocks(), iterations=-1)
    with pytest.raises(ValueError, match="--drop-labels: label 5 is not in the volume"):
        vm.mesh_labels(two_blocks(), drop_labels=[5])
    with pytest.raises(ValueError, match="tolerance: needs --size"):
        vm.mesh_labels(two_blocks(), tolerance=0.5)
    sized = vm.mesh_labels(two_blocks(), iterations=2, size=3.0, tolerance=0.3, min_size=1.5)
    assert sized.validate() == []
    with pytest.raises(TypeError, match="unknown option 'iteratons'"):
        vm.mesh_labels(two_blocks(), iteratons=3)
    with pytest.raises(TypeError, match="unknown option 'world'"):  # a file's option, not an array's
        vm.mesh_labels(two_blocks(), world="ras")
    with pytest.raises(TypeError, match="an array of integers .* got dtype complex128"):
        vm.mesh_labels(two_blocks().astype(np.complex128))
    with pytest.raises(ValueError, match="3-D array"):
        vm.mesh_labels(np.zeros((4, 4), dtype=np.int32))


def test_files_are_read_as_the_cli_reads_them(tmp_path):
    # A 3D Slicer segmentation: names from its segments, labels picked by name.
    n = 16
    data = two_blocks(n, np.uint8)
    header = ("NRRD0004\ntype: uchar\ndimension: 3\nsizes: 16 16 16\nspace: left-posterior-superior\n"
              "space directions: (1,0,0) (0,1,0) (0,0,1)\nkinds: domain domain domain\nencoding: raw\n"
              "space origin: (0,0,0)\nSegment0_ID:=a\nSegment0_Name:=liver\nSegment0_LabelValue:=3\n"
              "Segment1_ID:=b\nSegment1_Name:=tumour\nSegment1_LabelValue:=7\nSegment1_Color:=0 0.5 1\n\n")
    path = tmp_path / "organ.seg.nrrd"
    path.write_bytes(header.encode() + data.tobytes(order="F"))
    mesh = vm.mesh_file(str(path), iterations=2)
    assert mesh.phase_names == ["background", "liver", "tumour"]
    assert mesh.phase_colors == [None, None, (0.0, 0.5, 1.0)]  # the liver's header gives none
    if importlib.util.find_spec("meshio"):  # as test_meshes_round_trip_through_meshio, only with meshio
        assert mesh.to_meshio().field_data["phase_colors"].tolist() == [[7, 0, 0.5, 1]]
    ras = vm.mesh_file(str(path), iterations=0, world="ras", keep_labels=["tumour"])
    assert ras.phase_names == ["background", "tumour"] and ras.points[:, 0].max() <= 0
    with pytest.raises(OSError, match="missing.nrrd: cannot open"):
        vm.mesh_file(str(tmp_path / "missing.nrrd"))
    with pytest.raises(ValueError, match="no segment is named 'kidney'"):
        vm.mesh_file(str(path), drop_labels=["kidney"])
    # stats(field=...): offsets from the interface of the input the mesh was made from (read
    # with input options as keywords), in the h of the grid the mesh was made on, about twice
    # the voxel size with voxels_per_cell=2 (15 voxel spacings over 8 cells), whatever grid the
    # input would default to (its voxel grid, h 1); an input it was not made from is refused.
    coarse = vm.mesh_file(str(path), iterations=2, voxels_per_cell=2)
    offsets = coarse.stats(field=str(path), voxels_per_cell=2)["offsets"]
    assert offsets["spacing"] == pytest.approx(15 / 8) and offsets["surface"]["nodes"] > 50
    assert offsets["surface"]["max_h"] < 0.5 and "offsets" not in coarse.stats()
    assert coarse.stats(field=str(path))["offsets"]["spacing"] == offsets["spacing"]
    with pytest.raises(ValueError, match="voxels_per_cell= says how to read field=INPUT, which is not given"):
        coarse.stats(voxels_per_cell=2)
    with pytest.raises(ValueError, match="its phase 1 is 'liver', but the mesh calls phase 1 'tumour'"):
        ras.stats(field=str(path))  # made with the tumour alone kept
    # A closed mesh of the volume: stats(field=...) also locates its voxel centres, as the
    # CLI's stats --field does, with the counts label_agreement() gives for the same array.
    closed = vm.mesh_file(str(path), iterations=2, close=True)
    located = closed.stats(field=str(path))["label_agreement"]
    assert located == closed.label_agreement(data) and located["voxels"] == data.size
    with pytest.warns(UserWarning, match="voxel centres not located: the mesh is not closed"):
        assert "label_agreement" not in coarse.stats(field=str(path), voxels_per_cell=2)


def test_a_tiff_stack_written_by_pillow_is_the_volume_of_its_pages(tmp_path):
    # Fiji and micro-CT tools save label volumes as multi-page TIFFs: page k is slice z = k,
    # row j of it y = j. Pillow (an independent writer; LZW) writes one; the mesh is that of
    # the same labels as an array.
    image = pytest.importorskip("PIL.Image")
    labels = two_blocks(dtype=np.uint16)
    pages = [image.fromarray(np.ascontiguousarray(labels[:, :, k].T)) for k in range(labels.shape[2])]
    pages[0].save(tmp_path / "blocks.tif", save_all=True, append_images=pages[1:], compression="tiff_lzw")
    from_tiff = vm.mesh_file(str(tmp_path / "blocks.tif"), iterations=2)
    from_array = vm.mesh_labels(labels, iterations=2)
    assert np.array_equal(from_tiff.points, from_array.points)
    assert np.array_equal(from_tiff.triangles, from_array.triangles) and from_tiff.phase_labels == [0, 3, 7]
    # Pillow's TIFF says no voxel size: voxel_size gives one, as spacing gives an array's.
    sized = vm.mesh_file(str(tmp_path / "blocks.tif"), iterations=2, voxel_size=(0.5, 0.5, 0.55))
    assert np.array_equal(sized.points, vm.mesh_labels(labels, spacing=(0.5, 0.5, 0.55), iterations=2).points)
    pages[0].save(tmp_path / "slice.tif")
    with pytest.raises(ValueError, match="slice.tif: has one page, a 2-D image"):
        vm.mesh_file(str(tmp_path / "slice.tif"))


def test_meshes_round_trip_through_meshio(tmp_path):
    meshio = pytest.importorskip("meshio")
    mesh = vm.mesh_labels(two_blocks(), iterations=3)
    assert ".vtu" in vm.output_extensions()
    mesh.write(str(tmp_path / "blocks.vtu"))
    back = meshio.read(tmp_path / "blocks.vtu")
    assert np.allclose(back.points, mesh.points)
    assert np.array_equal(back.cells_dict["triangle"], mesh.triangles)
    assert np.array_equal(np.column_stack([back.cell_data["phase0"][0], back.cell_data["phase1"][0]]), mesh.phases)
    assert {k: list(v) for k, v in back.field_data.items()} == {"background": [0], "label3": [3], "label7": [7]}
    converted = mesh.to_meshio()
    converted.write(tmp_path / "converted.vtu")
    again = meshio.read(tmp_path / "converted.vtu")
    assert np.array_equal(again.cells_dict["triangle"], mesh.triangles)
    with pytest.raises(ValueError, match="unknown"):
        mesh.write(str(tmp_path / "blocks.xyz"))


def test_a_written_mesh_reads_back_as_the_mesh_it_was(tmp_path):
    # Meshed in one session, measured in the next: the PLY keeps what stats() and
    # label_agreement() need (the phases, their names, that the mesh is closed).
    mesh = vm.mesh_labels(two_blocks(), iterations=2, close=True)
    mesh.write(str(tmp_path / "blocks.ply"))
    back = vm.read_mesh(str(tmp_path / "blocks.ply"))
    assert np.array_equal(back.points, mesh.points) and np.array_equal(back.triangles, mesh.triangles)
    assert np.array_equal(back.phases, mesh.phases) and back.phase_names == mesh.phase_names
    assert back.validate() == [] and back.stats() == mesh.stats()
    assert back.label_agreement(two_blocks()) == mesh.label_agreement(two_blocks())
    mesh.write(str(tmp_path / "blocks.vtu"))
    with pytest.raises(OSError, match="blocks.vtu: a .vtu file, not a PLY: voronoimesh reads meshes back from PLY"):
        vm.read_mesh(str(tmp_path / "blocks.vtu"))
    with pytest.raises(OSError, match="gone.ply"):
        vm.read_mesh(str(tmp_path / "gone.ply"))


def big_labels():
    labels = np.zeros((48, 48, 48), dtype=np.int32, order="F")
    grid = np.indices(labels.shape)
    for k, centre in enumerate([(14, 14, 14), (30, 20, 26), (20, 32, 30)]):
        r2 = sum((grid[a] - centre[a]) ** 2 for a in range(3))
        labels[r2 < 12 ** 2] = k + 1
    return labels


def test_progress_reaches_the_callback_and_its_exception_stops_the_run():
    seen = []
    vm.mesh_labels(two_blocks(), iterations=2, progress=lambda stage, message: seen.append(stage))
    assert "create" in seen and seen.count("improve") >= 2

    class Stop(Exception):
        pass

    def stop_at_first_iteration(stage, message):
        if message.startswith("iteration 1 "):
            raise Stop(message)

    with pytest.raises(Stop, match="iteration 1 of 500"):
        vm.mesh_labels(big_labels(), iterations=500, progress=stop_at_first_iteration)


def test_ctrl_c_stops_a_run():
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        vm.mesh_labels(big_labels(), iterations=10000, stop_when_converged=False)  # long enough to interrupt
    timer.cancel()
    assert time.monotonic() - start < 30


def test_the_gil_is_released_while_meshing():
    ticks, done = [0], threading.Event()

    def count():
        while not done.is_set():
            ticks[0] += 1
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    start = time.monotonic()
    vm.mesh_labels(big_labels(), iterations=10)
    elapsed = time.monotonic() - start
    done.set()
    counter.join()
    # With the GIL held for the run the counter would stand still; released, it ticks
    # about once a millisecond (at least a tenth of that on a loaded machine).
    assert ticks[0] > 0.1 * elapsed * 1000, (ticks[0], elapsed)


def test_phase_values_from_a_simulation_mesh_as_a_scene_would():
    # Two spheres as signed distances on a 25^3 grid of the unit cube, plus the outside.
    n = 25
    x, y, z = np.meshgrid(*[np.linspace(0, 1, n)] * 3, indexing="ij")
    left = 0.25 - np.sqrt((x - 0.35) ** 2 + (y - 0.5) ** 2 + (z - 0.5) ** 2)
    right = 0.25 - np.sqrt((x - 0.65) ** 2 + (y - 0.5) ** 2 + (z - 0.5) ** 2)
    outside = np.zeros_like(left)
    mesh = vm.mesh_values([outside, left, right], spacing=(1 / (n - 1),) * 3, names=["outside", "left", "right"],
                          iterations=10)
    assert mesh.phase_names == ["outside", "left", "right"] and mesh.validate() == []
    assert set(map(tuple, mesh.phases)) == {(0, 1), (0, 2), (1, 2)}
    # The left|right surface is the plane x = 0.5, to well within a grid cell.
    between = mesh.triangles[(mesh.phases[:, 0] == 1) & (mesh.phases[:, 1] == 2)]
    assert np.abs(mesh.points[between.ravel(), 0] - 0.5).max() < 0.25 / (n - 1)
    # A 4-D array [phase, x, y, z] is the same phases.
    stacked = vm.mesh_values(np.stack([outside, left, right]), spacing=(1 / (n - 1),) * 3, iterations=10)
    assert np.array_equal(stacked.points, mesh.points)
    with pytest.raises(TypeError, match="unknown option 'drop_labels'"):
        vm.mesh_values([outside, left], drop_labels=[1])
    with pytest.raises(ValueError, match="same shape"):
        vm.mesh_values([outside, left[:-1]])
    with pytest.raises(ValueError, match="labels must be strictly increasing"):
        vm.mesh_values([outside, left, right], labels=[5, 5, 7])


def test_a_mesher_meshes_step_after_step_as_the_functions_do(tmp_path):
    # A simulation's steps: a block that grows, meshed with one Mesher.
    mesher = vm.Mesher(iterations=3, smoothing=0.8)
    for step, width in enumerate([4, 6, 8]):
        labels = two_blocks()
        labels[3:3 + width, 3:13, 3:13] = 3
        ours = mesher.mesh_labels(labels, spacing=(0.5, 0.5, 0.5))
        alone = vm.mesh_labels(labels, spacing=(0.5, 0.5, 0.5), iterations=3, smoothing=0.8)
        assert np.array_equal(ours.points, alone.points) and np.array_equal(ours.triangles, alone.triangles)
        assert ours.validate() == [] and mesher.meshes_made == step + 1
    # Its options are checked when it is made, not at the first step.
    with pytest.raises(ValueError, match="unknown pass 'smoth'"):
        vm.Mesher(pipeline="smoth,flip")
    with pytest.raises(ValueError, match="iterations"):
        vm.Mesher(iterations=-1)
    with pytest.raises(TypeError, match="unknown option 'colour'"):
        vm.Mesher(colour=1)
    # Label options do not apply to phase values: said at the call that gives values.
    x = np.linspace(-1, 1, 12)[:, None, None] * np.ones((12, 12, 12))
    with pytest.raises(TypeError, match="unknown option 'smoothing'"):
        mesher.mesh_values([x, -x])
    plain = vm.Mesher(iterations=2)
    assert plain.mesh_values([x, -x], names=["a", "b"]).phase_names == ["a", "b"]
