// python/src/options.cpp: see options.hpp.

#include "options.hpp"

#include <pybind11/stl.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace py = pybind11;

namespace vmpy {

namespace {

/// A label keyword's entry: an int is a value, a str a segment's name.
vm::LabelRef label_ref(const py::handle& h, const char* option) {
  if (py::isinstance<py::str>(h)) return h.cast<std::string>();
  if (py::isinstance<py::int_>(h)) return h.cast<int32_t>();
  throw py::type_error(std::string(option) + ": labels are ints (values) or strs (segment names), got " +
                       std::string(py::str(py::type::of(h).attr("__name__"))));
}

std::vector<vm::LabelRef> label_refs(const py::handle& h, const char* option) {
  std::vector<vm::LabelRef> out;
  for (const py::handle& item : h) out.push_back(label_ref(item, option));
  return out;
}

} // namespace

Options options_from(const py::kwargs& kwargs, Input input) {
  Options o;
  auto& m = o.mesh;
  auto& in = o.input;
  using Set = std::function<void(const py::handle&)>;
  const std::map<std::string, Set> meshing{
      {"iterations", [&](const py::handle& v) { m.iterations = v.cast<int>(); }},
      {"pipeline", [&](const py::handle& v) { m.pipeline = v.cast<std::string>(); }},
      {"size", [&](const py::handle& v) { m.size = v.cast<double>(); }},
      {"tolerance", [&](const py::handle& v) { m.tolerance = v.cast<double>(); }},
      {"min_size", [&](const py::handle& v) { m.min_size = v.cast<double>(); }},
      {"threads", [&](const py::handle& v) { m.threads = v.cast<int>(); }},
      {"close", [&](const py::handle& v) { m.close = v.cast<bool>(); }},
      {"snap", [&](const py::handle& v) { m.snap = in.snap = v.cast<double>(); }},
      {"validate", [&](const py::handle& v) { m.validate = v.cast<bool>(); }},
      {"stop_when_converged", [&](const py::handle& v) {
         if (v.is_none()) return m.stop_when_converged.reset(); // the input's default
         m.stop_when_converged = v.cast<bool>();
       }},
      {"crossing_guard", [&](const py::handle& v) { m.guard_crossings = v.cast<bool>(); }},
      {"check_crossings_every", [&](const py::handle& v) { m.check_crossings_every = v.cast<int>(); }},
      {"top_k", [&](const py::handle& v) { m.top_k = in.top_k = v.cast<int>(); }},
      {"lattice", [&](const py::handle& v) {
         if (v.is_none()) return m.lattice.reset(); // the input's default
         const auto name = v.cast<std::string>();
         if (name != "bcc" && name != "cube6") throw py::value_error("lattice: 'bcc' or 'cube6', got '" + name + "'");
         m.lattice = name == "bcc" ? vm::Lattice::bcc : vm::Lattice::cube6;
       }},
      {"grid", [&](const py::handle& v) {
         std::array<int, 3> cells{};
         if (py::isinstance<py::int_>(v)) cells.fill(v.cast<int>());
         else cells = v.cast<std::array<int, 3>>();
         m.grid = cells;
       }},
      {"progress", [&](const py::handle& v) {
         if (!v.is_none() && !PyCallable_Check(v.ptr())) throw py::type_error("progress: a callable (stage, message) or None");
         o.progress = py::reinterpret_borrow<py::object>(v);
       }},
  };
  const std::map<std::string, Set> labels{
      {"drop_labels", [&](const py::handle& v) { in.drop_labels = label_refs(v, "drop_labels"); }},
      {"keep_labels", [&](const py::handle& v) { in.keep_labels = label_refs(v, "keep_labels"); }},
      {"merge_labels", [&](const py::handle& v) {
         for (const py::handle& group : v) in.merge_labels.push_back(label_refs(group, "merge_labels"));
       }},
      {"background", [&](const py::handle& v) { in.background = v.cast<int32_t>(); }},
      {"no_background", [&](const py::handle& v) { in.no_background = v.cast<bool>(); }},
      {"signed_distance", [&](const py::handle& v) {
         in.label_function = v.cast<bool>() ? vm::LabelFunction::signed_distance : vm::LabelFunction::smoothed_indicator;
       }},
      {"smoothing", [&](const py::handle& v) { in.smoothing = v.cast<double>(); }},
      {"voxel_faithful", [&](const py::handle& v) { in.voxel_faithful = v.cast<bool>(); }},
      {"band", [&](const py::handle& v) { in.band = v.cast<double>(); }},
  };
  const std::map<std::string, Set> files_only{
      {"voxels_per_cell", [&](const py::handle& v) { in.voxels_per_cell = v.cast<double>(); }},
      {"ignore_direction", [&](const py::handle& v) { in.ignore_direction = v.cast<bool>(); }},
      {"voxel_size", [&](const py::handle& v) {
         if (py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v)) {
           in.voxel_size = vm::Vec3::Constant(v.cast<double>());
         } else {
           const auto s = v.cast<std::array<double, 3>>();
           in.voxel_size = vm::Vec3(s[0], s[1], s[2]);
         }
       }},
      {"world", [&](const py::handle& v) {
         const auto name = v.cast<std::string>();
         if (name != "file" && name != "lps" && name != "ras")
           throw py::value_error("world: 'file', 'lps' or 'ras', got '" + name + "'");
         in.world = name == "lps" ? vm::World::lps : name == "ras" ? vm::World::ras : vm::World::file;
       }},
  };
  // The tables this input takes: meshing options always, label options for
  // labels and files, volume-file options for files.
  std::vector<const std::map<std::string, Set>*> tables{&meshing};
  if (input != Input::values) tables.push_back(&labels);
  if (input == Input::file) tables.push_back(&files_only);
  for (const auto& [key, value] : kwargs) {
    const auto name = key.cast<std::string>();
    const Set* set = nullptr;
    for (const auto* table : tables)
      if (const auto it = table->find(name); it != table->end()) set = &it->second;
    if (!set) {
      std::string known;
      for (const auto* table : tables)
        for (const auto& entry : *table) known += (known.empty() ? "" : ", ") + entry.first;
      throw py::type_error("unknown option '" + name + "' (options: " + known + ")");
    }
    try {
      (*set)(value);
    } catch (const py::cast_error&) {
      throw py::type_error(name + ": cannot take a " + std::string(py::str(py::type::of(value).attr("__name__"))));
    }
  }
  return o;
}

void register_exceptions(py::module_& m) {
  static py::exception<vm::Error> error(m, "Error", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const vm::Cancelled& e) {
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    } catch (const vm::InvalidInput& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const vm::IoError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const vm::Error& e) {
      error(e.what());
    }
  });
}

} // namespace vmpy
