// python/src/module.cpp: the voronoimesh Python module (pybind11), a front end
// over the library's one run path (run/meshing.hpp): a scene from a label
// array or any input file, create_mesh(), improve_mesh() with the input's
// default pipeline, and the mesh as numpy arrays. Options are the CLI's, as
// keywords (options.cpp); the GIL is released while meshing and Ctrl-C stops a
// run between its steps (observer.hpp).

#include "observer.hpp"
#include "options.hpp"

#include <voronoimesh/io/ply.hpp>
#include <voronoimesh/voronoimesh.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace py = pybind11;

namespace {

/// A mesh held for Python: the arrays it hands out are views of it.
struct Mesh {
  vm::NodeMesh mesh;
};

/// A read-only (rows x cols) view of `data`, kept alive by `owner`.
template <class T>
py::array view(const T* data, size_t rows, size_t cols, py::handle owner) {
  py::array a(py::dtype::of<T>(), {rows, cols}, {cols * sizeof(T), sizeof(T)}, data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

/// Runs `make` (which meshes, returning a NodeMesh) with the GIL released,
/// raising the Python error that stopped it (Ctrl-C, or the progress callback's).
template <class Make>
std::unique_ptr<Mesh> run(vmpy::Observer& observer, Make&& make) {
  auto out = std::make_unique<Mesh>();
  try {
    py::gil_scoped_release released;
    out->mesh = make();
  } catch (const vm::Cancelled&) {
    observer.rethrow(); // the KeyboardInterrupt, or what the progress callback raised
    throw;
  }
  observer.rethrow();
  return out;
}

/// The grid of arrays shaped `shape` ([x, y, z] nodes) at `spacing` from `origin`.
vm::GridSpec node_grid(const py::ssize_t* shape, const std::array<double, 3>& spacing,
                       const std::array<double, 3>& origin, const char* what) {
  vm::GridSpec grid;
  for (int a = 0; a < 3; ++a) {
    if (shape[a] < 2) throw py::value_error(std::string(what) + ": at least 2 values along every axis, got " +
                                            std::to_string(shape[a]) + " along axis " + std::to_string(a));
    if (!(spacing[size_t(a)] > 0)) throw py::value_error("spacing: every voxel size must be above 0");
    grid.cells[size_t(a)] = int(shape[a] - 1);
    grid.domain.min[a] = origin[size_t(a)];
    grid.domain.max[a] = origin[size_t(a)] + spacing[size_t(a)] * double(shape[a] - 1);
  }
  return grid;
}

/// The labels of a real array whose every value is a whole number that fits in
/// 32 bits, as volume files of reals are read (nibabel's get_fdata() gives
/// float64 for any segmentation); a value that is not one is refused by its index.
py::array_t<int32_t, py::array::f_style> labels_from_whole_reals(const py::array& labels) {
  const auto reals = py::array_t<double, py::array::f_style | py::array::forcecast>::ensure(labels);
  if (!reals) throw py::error_already_set();
  py::array_t<int32_t, py::array::f_style> out(std::vector<py::ssize_t>(reals.shape(), reals.shape() + 3));
  const double* in = reals.data();
  int32_t* to = out.mutable_data();
  for (py::ssize_t i = 0; i < reals.size(); ++i) {
    const double x = in[i];
    if (!(x >= std::numeric_limits<int32_t>::min() && x <= std::numeric_limits<int32_t>::max() && x == std::trunc(x))) {
      const py::ssize_t nx = reals.shape(0), ny = reals.shape(1);
      throw py::value_error("labels: labels[" + std::to_string(i % nx) + ", " + std::to_string(i / nx % ny) + ", " +
                            std::to_string(i / nx / ny) + "] is " + py::repr(py::float_(x)).cast<std::string>() +
                            ", not a label: a real array is read as labels when every value is a whole 32-bit "
                            "number (a label map resampled with linear interpolation? resample it with nearest "
                            "neighbour)");
    }
    to[i] = int32_t(x);
  }
  return out;
}

/// A label array as the library takes it: 3-D, of integers that fit in 32 bits
/// (a wider array's values are checked, not cut: numpy's cast would turn label
/// 2^41 into 0 without a word), with x fastest in memory. An int32
/// Fortran-ordered array (nibabel's) is read where it lies; any other is
/// converted once. A boolean mask is labels 0 and 1; reals are labels when whole.
py::array_t<int32_t, py::array::f_style> int32_labels(const py::array& labels) {
  if (labels.ndim() != 3) throw py::value_error("labels: a 3-D array indexed [x, y, z] expected, got " +
                                                std::to_string(labels.ndim()) + " dimensions");
  const char kind = labels.dtype().kind();
  if (kind == 'f') return labels_from_whole_reals(labels);
  if (kind != 'i' && kind != 'u' && kind != 'b')
    throw py::type_error("labels: an array of integers (or of reals that are whole numbers) expected, got dtype " +
                         std::string(py::str(labels.dtype())));
  const bool wider = labels.dtype().itemsize() > 4 || (kind == 'u' && labels.dtype().itemsize() == 4);
  if (wider && labels.size() > 0)
    for (const char* end : {"min", "max"}) {
      const py::int_ value(labels.attr(end)()); // a Python int: compared exactly
      if (value < py::int_(std::numeric_limits<int32_t>::min()) || value > py::int_(std::numeric_limits<int32_t>::max()))
        throw py::value_error("labels: value " + py::repr(value).cast<std::string>() +
                              " is not a 32-bit label (-2147483648 to 2147483647)");
    }
  auto fortran = py::array_t<int32_t, py::array::f_style | py::array::forcecast>::ensure(labels);
  if (!fortran) throw py::error_already_set();
  return fortran;
}

/// The scene of a label array, made as options.input says.
vm::Scene labels_scene(const py::array& labels, const std::array<double, 3>& spacing,
                       const std::array<double, 3>& origin, const vmpy::Options& o) {
  const auto fortran = int32_labels(labels);
  const vm::GridSpec grid = node_grid(fortran.shape(), spacing, origin, "labels");
  py::gil_scoped_release released;
  return vm::scene_from_labels(grid, {fortran.data(), size_t(fortran.size())}, o.input, "labels");
}

/// The scene of phase values on a grid, one array per phase.
vm::Scene values_scene(const py::object& values, const std::array<double, 3>& spacing,
                       const std::array<double, 3>& origin, std::vector<std::string> names,
                       std::vector<int32_t> labels, const vmpy::Options& o) {
  // One array per phase, each indexed [x, y, z] and read where it lies when it
  // is float64 in Fortran order (x fastest), else converted once.
  std::vector<py::array_t<double, py::array::f_style | py::array::forcecast>> phases;
  for (const py::handle& item : values) {
    auto a = py::array_t<double, py::array::f_style | py::array::forcecast>::ensure(item);
    if (!a) throw py::error_already_set();
    if (a.ndim() != 3) throw py::value_error("values: one 3-D array per phase, indexed [x, y, z]");
    if (!phases.empty() && !std::equal(a.shape(), a.shape() + 3, phases.front().shape()))
      throw py::value_error("values: every phase's array must have the same shape");
    phases.push_back(std::move(a));
  }
  if (phases.empty()) throw py::value_error("values: one 3-D array per phase expected, got none");
  const vm::GridSpec grid = node_grid(phases.front().shape(), spacing, origin, "values");
  std::vector<std::span<const double>> spans;
  for (const auto& a : phases) spans.emplace_back(a.data(), size_t(a.size()));
  vm::PhaseValuesOptions options;
  options.names = std::move(names);
  options.labels = std::move(labels);
  options.top_k = o.mesh.top_k;
  options.source = "values";
  py::gil_scoped_release released;
  return vm::scene_from_phase_values(grid, spans, options);
}

std::unique_ptr<Mesh> mesh_labels(const py::array& labels, const std::array<double, 3>& spacing,
                                  const std::array<double, 3>& origin, const py::kwargs& kwargs) {
  const vmpy::Options o = vmpy::options_from(kwargs, vmpy::Input::labels); // before copying anything
  vmpy::Observer observer(o.progress);
  const vm::Scene scene = labels_scene(labels, spacing, origin, o);
  return run(observer, [&] { return vm::mesh_scene(scene, o.mesh, &observer); });
}

std::unique_ptr<Mesh> mesh_values(const py::object& values, const std::array<double, 3>& spacing,
                                  const std::array<double, 3>& origin, std::vector<std::string> names,
                                  std::vector<int32_t> labels, const py::kwargs& kwargs) {
  const vmpy::Options o = vmpy::options_from(kwargs, vmpy::Input::values); // before copying anything
  vmpy::Observer observer(o.progress);
  const vm::Scene scene = values_scene(values, spacing, origin, std::move(names), std::move(labels), o);
  return run(observer, [&] { return vm::mesh_scene(scene, o.mesh, &observer); });
}

std::unique_ptr<Mesh> mesh_file(const std::string& path, const py::kwargs& kwargs) {
  const vmpy::Options o = vmpy::options_from(kwargs, vmpy::Input::file);
  vmpy::Observer observer(o.progress);
  return run(observer, [&] { return vm::mesh_scene(vm::read_input(path, o.input, &observer), o.mesh, &observer); });
}

/// voronoimesh.Mesher: one set of options for mesh after mesh (vm::Mesher),
/// checked when it is made; the input options among them apply per input kind.
class Mesher {
public:
  explicit Mesher(const py::kwargs& kwargs)
      : kwargs_(kwargs), options_(vmpy::options_from(kwargs, vmpy::Input::file)),
        observer_(options_.progress), mesher_(options_.mesh, &observer_) {}

  std::unique_ptr<Mesh> labels(const py::array& labels, const std::array<double, 3>& spacing,
                               const std::array<double, 3>& origin) {
    const vm::Scene scene = labels_scene(labels, spacing, origin, vmpy::options_from(kwargs_, vmpy::Input::labels));
    return run(observer_, [&] { return mesher_.mesh(scene); });
  }
  std::unique_ptr<Mesh> values(const py::object& values, const std::array<double, 3>& spacing,
                               const std::array<double, 3>& origin, std::vector<std::string> names,
                               std::vector<int32_t> labels) {
    const vm::Scene scene = values_scene(values, spacing, origin, std::move(names), std::move(labels),
                                         vmpy::options_from(kwargs_, vmpy::Input::values));
    return run(observer_, [&] { return mesher_.mesh(scene); });
  }
  std::unique_ptr<Mesh> file(const std::string& path) {
    return run(observer_, [&] { return mesher_.mesh(mesher_.read(path, options_.input)); });
  }
  size_t meshes_made() const { return mesher_.meshes_made(); }

private:
  py::kwargs kwargs_;
  vmpy::Options options_;
  vmpy::Observer observer_;
  vm::Mesher mesher_;
};

py::list junctions(const Mesh& self) {
  const vm::Junctions j = vm::find_junctions(self.mesh);
  py::list curves;
  for (const vm::TripleCurve& c : j.curves) {
    py::list phases;
    for (int32_t p : c.phases) phases.append(self.mesh.label_of(p));
    py::dict curve;
    curve["phases"] = py::tuple(phases);
    curve["nodes"] = py::array_t<int32_t>(py::ssize_t(c.nodes.size()), c.nodes.data());
    curve["closed"] = c.closed();
    curves.append(curve);
  }
  return curves;
}

} // namespace

PYBIND11_MODULE(_voronoimesh, m) {
  m.doc() = "Meshes of interconnected surfaces (Saye's Voronoi implicit interface method).";
  vmpy::register_exceptions(m);

  py::class_<Mesh>(m, "Mesh", "An interface mesh: triangles of every surface between phases, sharing nodes at junctions.")
      .def_property_readonly(
          "points", [](py::object self) {
            const auto& m = self.cast<const Mesh&>().mesh;
            return view(m.points.empty() ? nullptr : m.points[0].data(), m.points.size(), 3, self);
          },
          "Node positions, N x 3 float64 (a read-only view)")
      .def_property_readonly(
          "triangles", [](py::object self) {
            const auto& m = self.cast<const Mesh&>().mesh;
            return view(m.triangles.empty() ? nullptr : m.triangles[0].data(), m.triangles.size(), 3, self);
          },
          "Node ids of each triangle, M x 3 int32 (a read-only view); the normal points from phases[t, 0] into phases[t, 1]")
      .def_property_readonly(
          "phases", [](const Mesh& self) {
            py::array_t<int32_t> out({py::ssize_t(self.mesh.pairs.size()), py::ssize_t(2)});
            auto w = out.mutable_unchecked<2>();
            for (size_t t = 0; t < self.mesh.pairs.size(); ++t)
              for (int k = 0; k < 2; ++k) w(py::ssize_t(t), k) = self.mesh.label_of(self.mesh.pairs[t][size_t(k)]);
            return out;
          },
          "The phase labels on either side of each triangle, M x 2 int32 (label values, as in every output file)")
      .def_property_readonly(
          "phase_names", [](const Mesh& self) { return self.mesh.phase_names; }, "Each phase's name, by phase id")
      .def_property_readonly(
          "phase_labels", [](const Mesh& self) {
            std::vector<int32_t> labels;
            for (size_t p = 0; p < self.mesh.phase_names.size(); ++p) labels.push_back(self.mesh.label_of(int32_t(p)));
            return labels;
          },
          "The label each phase shows, by phase id")
      .def_property_readonly(
          "phase_colors", [](const Mesh& self) {
            py::list colors;
            for (size_t p = 0; p < self.mesh.phase_names.size(); ++p) {
              const auto rgb = p < self.mesh.phase_colors.size() ? self.mesh.phase_colors[p] : std::nullopt;
              colors.append(rgb ? py::object(py::make_tuple((*rgb)[0], (*rgb)[1], (*rgb)[2])) : py::object(py::none()));
            }
            return colors;
          },
          "Each phase's display colour, by phase id: (red, green, blue) in [0, 1] (a 3D Slicer segment's colour), "
          "or None")
      .def(
          "validate", [](const Mesh& self) { return vm::validate(self.mesh).problems; },
          "The problems the validator finds (every phase closed and 2-manifold, junctions consistent, no duplicate "
          "or zero-area triangles, no node without a triangle; at most 20, one line each): an empty list for a valid "
          "mesh")
      .def("junctions", &junctions,
           "The triple curves: a list of dicts with 'phases' (labels), 'nodes' (int32 ids along the curve) and 'closed'")
      .def(
          "stats_json",
          [](const Mesh& self, size_t worst, size_t folds, const std::string& field, const py::kwargs& kwargs) {
            std::vector<std::pair<std::string, std::string>> more;
            std::string not_located; // said as a warning once the GIL is held again
            // Input options only say how to read the field: without one they would do nothing.
            if (field.empty() && !kwargs.empty())
              throw py::value_error("stats: " + py::str(kwargs.begin()->first).cast<std::string>() +
                                    "= says how to read field=INPUT, which is not given");
            if (!field.empty()) {
              const vmpy::Options o = vmpy::options_from(kwargs, vmpy::Input::file);
              py::gil_scoped_release released;
              const vm::Scene scene = vm::read_input(field, o.input);
              const vm::MeshOffsets at = vm::offsets_from_input(self.mesh, "the mesh", scene, field);
              more.emplace_back("offsets", vm::to_json(at.offsets, self.mesh, at.spacing));
              // A label volume's voxel centres, located in a closed mesh (as 'voronoimesh stats --field').
              if (const auto agreement = vm::label_agreement_from_input(self.mesh, scene, field, o.input))
                more.emplace_back("label_agreement", vm::to_json(*agreement));
              not_located = vm::voxel_centres_not_located(self.mesh, scene);
            }
            if (!not_located.empty() && PyErr_WarnEx(PyExc_UserWarning, not_located.c_str(), 1) < 0)
              throw py::error_already_set();
            return vm::to_json(vm::compute_stats(self.mesh), vm::worst_triangles(self.mesh, worst), &self.mesh,
                               vm::sharpest_folds(self.mesh, folds), more);
          },
          py::arg("worst") = 0, py::arg("folds") = 0, py::arg("field") = "",
          "Counts and quality, as 'voronoimesh stats --json [--worst N] [--folds M] [--field INPUT]' prints them: "
          "with worst=N, also the N triangles of lowest quality and what meets at their corners "
          "('worst_triangles'); with folds=M, the M sharpest folds ('sharpest_folds'); with field=INPUT (the "
          "file the mesh was made from, with its input options as keywords), how far the nodes lie from its "
          "interface ('offsets') and, for a label volume and a closed mesh, where its voxel centres lie "
          "('label_agreement', as label_agreement())")
      .def(
          "label_agreement_json",
          [](const Mesh& self, const py::array& labels, const std::array<double, 3>& spacing,
             const std::array<double, 3>& origin, int margin) {
            const auto fortran = int32_labels(labels);
            const vm::PointGrid centres{Eigen::Map<const vm::Vec3>(origin.data()),
                                        Eigen::Map<const vm::Vec3>(spacing.data()),
                                        {fortran.shape(0), fortran.shape(1), fortran.shape(2)}};
            py::gil_scoped_release released;
            return vm::to_json(
                vm::label_agreement(self.mesh, centres, {fortran.data(), size_t(fortran.size())}, margin));
          },
          py::arg("labels"), py::arg("spacing") = std::array<double, 3>{1, 1, 1},
          py::arg("origin") = std::array<double, 3>{0, 0, 0}, py::arg("margin") = 1,
          "Where the voxel centres of a label array (indexed [x, y, z], voxel centres at origin + spacing * "
          "index, as for mesh_labels()) lie in this closed mesh (close=True), as JSON: 'voxels' counted "
          "(every centre; the outer layer's, on the box faces, a thousandth of a spacing inside), 'in_phase' (in a "
          "phase of their own label), 'interior' (those whose neighbours within `margin` voxels share their label) "
          "and 'interior_in_phase', 'undecided', and per label 'labels'")
      .def(
          "write", [](const Mesh& self, const std::string& path, bool ascii) {
            vm::RunOutputs outputs;
            outputs.mesh = path;
            outputs.ascii = ascii;
            py::gil_scoped_release released;
            vm::write_outputs(self.mesh, outputs);
          },
          py::arg("path"), py::arg("ascii") = false,
          "Writes the mesh; the extension picks the format (.ply .obj .stl .msh .vtu .vtp .mesh)")
      .def_property_readonly(
          "num_triangles", [](const Mesh& self) { return self.mesh.num_triangles(); }, "Number of triangles");

  m.def("mesh_labels", &mesh_labels, py::arg("labels"), py::arg("spacing") = std::array<double, 3>{1, 1, 1},
        py::arg("origin") = std::array<double, 3>{0, 0, 0},
        "Meshes a label volume given as a 3-D array of integer labels (or of reals that are whole numbers, or a "
        "boolean mask) indexed [x, y, z] (voxel centres at origin + spacing * index), with the options of "
        "'voronoimesh mesh' as keywords.");
  m.def("mesh_values", &mesh_values, py::arg("values"), py::arg("spacing") = std::array<double, 3>{1, 1, 1},
        py::arg("origin") = std::array<double, 3>{0, 0, 0}, py::arg("names") = std::vector<std::string>{},
        py::arg("labels") = std::vector<int32_t>{},
        "Meshes phase functions given by their values on a grid (a level-set or phase-field simulation's): one "
        "3-D float array per phase indexed [x, y, z] (or a 4-D array [phase, x, y, z]), larger = more inside, "
        "interpolated trilinearly; names and labels optional, labels strictly increasing.");
  m.def("mesh_file", &mesh_file, py::arg("path"),
        "Meshes any input 'voronoimesh mesh' reads (a scene, volume, segmentation, grain map or point cloud), "
        "with its options as keywords.");
  m.def("output_extensions", &vm::io::output_extensions, "The extensions Mesh.write() knows");
  m.def(
      "read_mesh",
      [](const std::string& path) {
        auto out = std::make_unique<Mesh>();
        py::gil_scoped_release released;
        out->mesh = vm::io::read_ply(path);
        return out;
      },
      py::arg("path"),
      "Reads a mesh written as PLY (Mesh.write('out.ply'), 'voronoimesh mesh -o out.ply'), as 'voronoimesh "
      "stats' reads it: its phases, their names and colours, the grid spacing and whether it is closed, so that "
      "stats() and label_agreement() of the mesh read back are those of the mesh written. A mesh that is not "
      "valid is read too: validate() names its problems. Raises OSError naming the file for one that cannot be "
      "read or is not a PLY.");

  py::class_<Mesher>(m, "Mesher",
                     "Meshes input after input with one set of options (a simulation's steps, a series of volumes): "
                     "the options are those of mesh_labels() and mesh_file(), checked once, here")
      .def(py::init<const py::kwargs&>())
      .def("mesh_labels", &Mesher::labels, py::arg("labels"), py::arg("spacing") = std::array<double, 3>{1, 1, 1},
           py::arg("origin") = std::array<double, 3>{0, 0, 0}, "As voronoimesh.mesh_labels(), with the Mesher's options")
      .def("mesh_values", &Mesher::values, py::arg("values"), py::arg("spacing") = std::array<double, 3>{1, 1, 1},
           py::arg("origin") = std::array<double, 3>{0, 0, 0}, py::arg("names") = std::vector<std::string>{},
           py::arg("labels") = std::vector<int32_t>{}, "As voronoimesh.mesh_values(), with the Mesher's options")
      .def("mesh_file", &Mesher::file, py::arg("path"), "As voronoimesh.mesh_file(), with the Mesher's options")
      .def_property_readonly("meshes_made", &Mesher::meshes_made, "Meshes made so far");
}
