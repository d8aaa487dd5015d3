/// @file io/dream3d.cpp
/// DREAM.3D files (.dream3d, HDF5) through the HDF5 C library: the grain map
/// (`FeatureIds`, one grain id per cell) of an image geometry, as a label
/// volume whose labels are grains, named after them and, when the file has a
/// feature-level `Phases` array, after their phase: by the phase's name when
/// an ensemble-level array names the phases, else by its number. Two layouts:
///
/// - SIMPL (DREAM.3D 6.x): `/DataContainers/<container>/_SIMPL_GEOMETRY` holds
///   datasets DIMENSIONS, ORIGIN and SPACING (RESOLUTION in older files); the
///   cell data is a group beside it holding FeatureIds.
/// - DREAM3D-NX (7.x): `/DataStructure/<geometry>` is a group with attributes
///   _DIMENSIONS, _ORIGIN and _SPACING; its cell data is a group in it.
///
/// Both store x fastest (datasets shaped z, y, x, components), the origin is
/// the corner of the first cell, and dimensions are x, y, z.

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/io/volume.hpp"

#include "core/distinct.hpp"
#include "core/memory.hpp"
#include "core/text.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace vm::io {

namespace {

using detail::cat;

/// An HDF5 handle, closed with `close` however we leave.
class Handle {
public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

/// The names of the links in group `g`, in name order.
std::vector<std::string> children(hid_t g) {
  std::vector<std::string> names;
  H5Literate(g, H5_INDEX_NAME, H5_ITER_INC, nullptr,
             [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
               static_cast<std::vector<std::string>*>(out)->emplace_back(name);
               return 0;
             },
             &names);
  return names;
}

/// Whether `name` in `g` is an object of this type (H5I_GROUP, H5I_DATASET).
bool is(hid_t g, const std::string& name, H5I_type_t type) {
  if (H5Lexists(g, name.c_str(), H5P_DEFAULT) <= 0) return false;
  const Handle o(H5Oopen(g, name.c_str(), H5P_DEFAULT), H5Oclose);
  return o.ok() && H5Iget_type(o.get()) == type;
}

/// The values of a numeric dataset or attribute of `count` elements, as doubles.
template <class Open, class Read>
std::optional<std::vector<double>> read_numbers(Open open, herr_t (*close)(hid_t), hid_t (*space_of)(hid_t), Read read) {
  const Handle object(open(), close);
  if (!object.ok()) return std::nullopt;
  const Handle space(space_of(object.get()), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  if (n <= 0 || n > 64) return std::nullopt;
  std::vector<double> values(static_cast<size_t>(n));
  if (read(object.get(), values.data()) < 0) return std::nullopt;
  return values;
}

std::optional<std::vector<double>> attribute(hid_t object, const char* name) {
  if (H5Aexists(object, name) <= 0) return std::nullopt;
  return read_numbers([&] { return H5Aopen(object, name, H5P_DEFAULT); }, H5Aclose, H5Aget_space,
                      [](hid_t a, double* out) { return H5Aread(a, H5T_NATIVE_DOUBLE, out); });
}

std::optional<std::vector<double>> small_dataset(hid_t g, const char* name) {
  if (!is(g, name, H5I_DATASET)) return std::nullopt;
  return read_numbers([&] { return H5Dopen2(g, name, H5P_DEFAULT); }, H5Dclose, H5Dget_space,
                      [](hid_t d, double* out) { return H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out); });
}

/// An image geometry with a grain map: where it is and what it says.
struct Grains {
  std::string where;            ///< the path of its FeatureIds, for messages
  std::string cell_group;       ///< the group holding FeatureIds, within `parent`
  std::string parent;           ///< the geometry (NX) or data container (SIMPL)
  std::vector<double> dims, origin, spacing;
};

/// The groups of `parent` holding a dataset `name` (the attribute matrices).
std::vector<std::string> groups_holding(hid_t parent, const std::string& name) {
  std::vector<std::string> out;
  for (const std::string& c : children(parent))
    if (is(parent, c, H5I_GROUP)) {
      const Handle g(H5Gopen2(parent, c.c_str(), H5P_DEFAULT), H5Gclose);
      if (g.ok() && is(g.get(), name, H5I_DATASET)) out.push_back(c);
    }
  return out;
}

/// Every image geometry of the file that has a FeatureIds array.
std::vector<Grains> find_grains(hid_t file, const std::string& path) {
  std::vector<Grains> found;
  auto geometry_error = [&](const std::string& where, const char* what) {
    return InvalidInput(located(path, cat(where, ": ", what)));
  };
  if (is(file, "DataStructure", H5I_GROUP)) { // DREAM3D-NX
    const Handle root(H5Gopen2(file, "DataStructure", H5P_DEFAULT), H5Gclose);
    for (const std::string& name : children(root.get())) {
      if (!is(root.get(), name, H5I_GROUP)) continue;
      const Handle geometry(H5Gopen2(root.get(), name.c_str(), H5P_DEFAULT), H5Gclose);
      auto dims = attribute(geometry.get(), "_DIMENSIONS");
      if (!dims) continue; // not an image geometry
      for (const std::string& cells : groups_holding(geometry.get(), "FeatureIds")) {
        Grains g{cat("DataStructure/", name, "/", cells, "/FeatureIds"), cells, "DataStructure/" + name, *dims, {}, {}};
        const std::string where = "DataStructure/" + name;
        g.origin = attribute(geometry.get(), "_ORIGIN").value_or(std::vector<double>{});
        g.spacing = attribute(geometry.get(), "_SPACING").value_or(std::vector<double>{});
        if (g.spacing.empty()) throw geometry_error(where, "an image geometry without _SPACING");
        found.push_back(std::move(g));
      }
    }
  } else if (is(file, "DataContainers", H5I_GROUP)) { // SIMPL
    const Handle root(H5Gopen2(file, "DataContainers", H5P_DEFAULT), H5Gclose);
    for (const std::string& name : children(root.get())) {
      if (!is(root.get(), name, H5I_GROUP)) continue;
      const Handle container(H5Gopen2(root.get(), name.c_str(), H5P_DEFAULT), H5Gclose);
      if (!is(container.get(), "_SIMPL_GEOMETRY", H5I_GROUP)) continue;
      const Handle geometry(H5Gopen2(container.get(), "_SIMPL_GEOMETRY", H5P_DEFAULT), H5Gclose);
      auto dims = small_dataset(geometry.get(), "DIMENSIONS");
      if (!dims) continue; // not an image geometry
      const std::string where = cat("DataContainers/", name, "/_SIMPL_GEOMETRY");
      for (const std::string& cells : groups_holding(container.get(), "FeatureIds")) {
        Grains g{cat("DataContainers/", name, "/", cells, "/FeatureIds"), cells, "DataContainers/" + name, *dims, {}, {}};
        g.origin = small_dataset(geometry.get(), "ORIGIN").value_or(std::vector<double>{});
        auto spacing = small_dataset(geometry.get(), "SPACING");
        if (!spacing) spacing = small_dataset(geometry.get(), "RESOLUTION"); // DREAM.3D before 6.5
        if (!spacing) throw geometry_error(where, "an image geometry without SPACING");
        g.spacing = *spacing;
        found.push_back(std::move(g));
      }
    }
  } else {
    throw InvalidInput(located(path, "has neither DataContainers (DREAM.3D 6) nor DataStructure (DREAM3D-NX 7): "
                                     "not a DREAM.3D file"));
  }
  return found;
}

/// Reads an integer dataset of `count` values into int32 labels, refusing values int32 cannot hold.
std::vector<int32_t> read_ids(hid_t d, int64_t count, const std::string& path, const std::string& where) {
  const Handle type(H5Dget_type(d), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_INTEGER)
    throw InvalidInput(located(path, cat(where, ": holds no integers (grain ids are integers)")));
  std::vector<int64_t> wide(static_cast<size_t>(count));
  if (H5Dread(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, wide.data()) < 0)
    throw InvalidInput(located(path, cat(where, ": cannot be read (truncated or corrupt)")));
  std::vector<int32_t> ids(wide.size());
  for (size_t i = 0; i < wide.size(); ++i) {
    if (wide[i] < std::numeric_limits<int32_t>::min() || wide[i] > std::numeric_limits<int32_t>::max())
      throw InvalidInput(located(path, cat(where, ": id ", wide[i], " at cell ", i, " does not fit in 32 bits")));
    ids[i] = int32_t(wide[i]);
  }
  return ids;
}

/// The phase of each grain (by grain id) from a feature-level `Phases` array
/// beside the cell data, if there is one with an entry for every grain.
std::vector<int32_t> phases_of_grains(hid_t parent, const Grains& g, int32_t max_id, const std::string& path) {
  for (const std::string& group : groups_holding(parent, "Phases")) {
    if (group == g.cell_group) continue; // the cells' phases, not the grains'
    const Handle features(H5Gopen2(parent, group.c_str(), H5P_DEFAULT), H5Gclose);
    const Handle d(H5Dopen2(features.get(), "Phases", H5P_DEFAULT), H5Dclose);
    const Handle space(H5Dget_space(d.get()), H5Sclose);
    const hssize_t n = H5Sget_simple_extent_npoints(space.get());
    const std::string where = cat(g.parent, "/", group, "/Phases");
    const int64_t grains = int64_t(max_id) + 1;
    if (n < grains) continue;
    // One entry per grain id; a damaged size must not decide what we allocate.
    if (n > 2 * grains + 1024)
      throw InvalidInput(located(path, cat(where, ": has ", n, " entries for grain ids up to ", max_id)));
    return read_ids(d.get(), n, path, where);
  }
  return {};
}

/// The strings of a one-column string dataset (variable or fixed length, as
/// DREAM.3D and h5py write them), refusing anything else in one line.
std::vector<std::string> read_strings(hid_t d, const std::string& path, const std::string& where) {
  auto malformed = [&](const std::string& what) { return InvalidInput(located(path, cat(where, ": ", what))); };
  const Handle type(H5Dget_type(d), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING) throw malformed("holds no strings (phase names are strings)");
  const Handle space(H5Dget_space(d), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  hsize_t dims[2] = {0, 1};
  if (rank < 1 || rank > 2 || H5Sget_simple_extent_dims(space.get(), dims, nullptr) < 0 || dims[1] != 1)
    throw malformed("is not a list of names (one column)");
  // One name per phase, and phase ids are small: a damaged size must not decide what we allocate.
  if (dims[0] > kMaxPhases) throw malformed(cat("has ", dims[0], " names; at most ", kMaxPhases, " phases"));
  const size_t n = size_t(dims[0]);
  std::vector<std::string> names(n);
  // Read in the file's character set (h5py writes UTF-8): HDF5 converts between none.
  const Handle memory(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_cset(memory.get(), H5Tget_cset(type.get()));
  if (H5Tis_variable_str(type.get()) > 0) {
    H5Tset_size(memory.get(), H5T_VARIABLE);
    std::vector<char*> text(n, nullptr);
    if (H5Dread(d, memory.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, text.data()) < 0)
      throw malformed("cannot be read (truncated or corrupt)");
    for (size_t i = 0; i < n; ++i)
      if (text[i]) names[i] = text[i];
    H5Dvlen_reclaim(memory.get(), space.get(), H5P_DEFAULT, text.data()); // H5Treclaim from HDF5 1.12
  } else {
    const size_t width = H5Tget_size(type.get());
    if (width == 0 || width > 4096) throw malformed(cat("holds names of ", width, " bytes each"));
    H5Tset_size(memory.get(), width);
    std::vector<char> text(n * width);
    if (H5Dread(d, memory.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, text.data()) < 0)
      throw malformed("cannot be read (truncated or corrupt)");
    for (size_t i = 0; i < n; ++i) {
      std::string name(text.data() + i * width, width);
      name.erase(std::min(name.find('\0'), name.size())); // null-terminated or null-padded
      name.erase(name.find_last_not_of(' ') + 1);          // space-padded
      names[i] = std::move(name);
    }
  }
  return names;
}

/// The phases' names, by phase id, from an ensemble-level string array in a
/// group beside the cell data: `PhaseName` (DREAM.3D 6's StatsGenerator and
/// Create Ensemble Info), `PhaseNames` (DREAM3D-NX's Create Ensemble Info) or
/// else `MaterialName` (the EBSD readers of both). Entry 0 is DREAM.3D's
/// placeholder for cells of no phase. Empty when there is none. `where` gets
/// the dataset's path, for messages.
std::vector<std::string> phase_names(hid_t parent, const Grains& g, const std::string& path, std::string& where) {
  for (const char* array : {"PhaseName", "PhaseNames", "MaterialName"})
    for (const std::string& group : groups_holding(parent, array)) {
      if (group == g.cell_group) continue;
      const Handle features(H5Gopen2(parent, group.c_str(), H5P_DEFAULT), H5Gclose);
      const Handle d(H5Dopen2(features.get(), array, H5P_DEFAULT), H5Dclose);
      where = cat(g.parent, "/", group, "/", array);
      return read_strings(d.get(), path, where);
    }
  return {};
}

/// The name of grain `id` of phase `phase`: grain<id>-<phase's name> when the
/// file names the phases, else grain<id>-phase<phase>.
std::string grain_name(int32_t id, int32_t phase, const std::vector<std::string>& names, const std::string& path,
                       const std::string& where) {
  if (phase >= 0 && size_t(phase) >= names.size() && !names.empty())
    throw InvalidInput(located(path, cat(where, ": has ", names.size(), " names (phases 0 to ", names.size() - 1,
                                         "), but grain ", id, " is of phase ", phase)));
  if (phase >= 0 && !names.empty() && !names[size_t(phase)].empty()) return cat("grain", id, "-", names[size_t(phase)]);
  return cat("grain", id, "-phase", phase);
}

} // namespace

Volume read_dream3d(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw IoError(located(path, "cannot open (No such file or directory)"));
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); // failures are reported here, as one line each
  if (H5Fis_hdf5(path.c_str()) <= 0) throw InvalidInput(located(path, "not an HDF5 file (a .dream3d file is one)"));
  const Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.ok()) throw IoError(located(path, "cannot open it as an HDF5 file"));
  const std::vector<Grains> found = find_grains(file.get(), path);
  if (found.empty()) throw InvalidInput(located(path, "has no image geometry with a FeatureIds array (a grain map)"));
  if (found.size() > 1) {
    std::string list;
    for (const Grains& g : found) list += (list.empty() ? "" : ", ") + g.where;
    throw InvalidInput(located(path, cat("has ", found.size(), " grain maps (", list, "); voronoimesh reads one per file")));
  }
  const Grains& g = found.front();
  if (g.dims.size() != 3 || g.spacing.size() != 3 || (!g.origin.empty() && g.origin.size() != 3))
    throw InvalidInput(located(path, cat(g.parent, ": dimensions, spacing and origin need 3 values each")));
  Volume v;
  for (int a = 0; a < 3; ++a) {
    const double d = g.dims[size_t(a)], s = g.spacing[size_t(a)];
    if (!(d >= 1 && d <= double(1 << 30) && d == std::floor(d)))
      throw InvalidInput(located(path, cat(g.parent, ": dimension ", d, " along axis ", a, " is not a cell count")));
    if (!(std::isfinite(s) && s > 0))
      throw InvalidInput(located(path, cat(g.parent, ": spacing ", s, " along axis ", a, "; it must be positive")));
    v.size[size_t(a)] = int64_t(d);
    v.spacing[a] = s;
    // DREAM.3D's origin is the corner of the first cell; a Volume's, its centre.
    v.origin[a] = (g.origin.empty() ? 0.0 : g.origin[size_t(a)]) + 0.5 * s;
  }
  detail::refuse_beyond_memory(double(v.voxel_count()) * 12, path, cat("reading ", v.voxel_count(), " grain ids"));
  const Handle parent(H5Gopen2(file.get(), g.parent.c_str(), H5P_DEFAULT), H5Gclose);
  const Handle cells(H5Gopen2(parent.get(), g.cell_group.c_str(), H5P_DEFAULT), H5Gclose);
  const Handle ids(H5Dopen2(cells.get(), "FeatureIds", H5P_DEFAULT), H5Dclose);
  const Handle space(H5Dget_space(ids.get()), H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != v.voxel_count())
    throw InvalidInput(located(path, cat(g.where, ": holds ", H5Sget_simple_extent_npoints(space.get()),
                                         " values for ", v.voxel_count(), " cells (", v.size[0], " x ", v.size[1],
                                         " x ", v.size[2], ")")));
  v.integer = true;
  v.labels = read_ids(ids.get(), v.voxel_count(), path, g.where);
  // Names: grain<id>, and its phase when the file has the grains' phases.
  const std::vector<int32_t> present = detail::distinct(v.labels);
  const std::vector<int32_t> phase = phases_of_grains(parent.get(), g, present.back(), path);
  std::string names_at;
  const std::vector<std::string> names = phase.empty() ? std::vector<std::string>{}
                                                       : phase_names(parent.get(), g, path, names_at);
  for (int32_t id : present)
    if (id > 0) {
      Segment s;
      s.label = id;
      s.name = phase.empty() ? cat("grain", id) : grain_name(id, phase[size_t(id)], names, path, names_at);
      v.segments.push_back(std::move(s));
    }
  return v;
}

} // namespace vm::io
