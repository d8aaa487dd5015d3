// cgal_label_mesher: the CGAL side of bench/race.sh. Meshes a labelled 3D
// image with CGAL Mesh_3 (Labeled_mesh_domain_3::create_labeled_image_mesh_domain
// and make_mesh_3) and writes the surface between subdomains as a voronoimesh
// PLY (docs/formats.md), so `voronoimesh stats` can measure and validate it
// exactly as it does voronoimesh's own meshes.
//
//   cgal_label_mesher IN.inr[.gz] OUT.ply [--facet-size V] [--facet-distance V]
//                     [--facet-angle DEG] [--cell-ratio R] [--threads N]
//                     [--optimise] [--manifold] [--seed S] [--diagnose]
//
// Sizes are in voxels of the smallest spacing (as voronoimesh's
// --voxels-per-cell). Defaults: facet size 2, distance 0.5, angle 30; cells only
// bounded by radius-edge ratio 3 (no cell size: we compare surfaces, and a
// small cell size would only add interior refinement to CGAL's time).
// Sliver perturbation and exudation, which make_mesh_3 runs by default, are
// off unless --optimise: they improve tetrahedra, not the surface (perturbation
// may move surface vertices a little, never off the surface approximation
// the facet criteria already accepted), so a surface race should not charge
// them to CGAL. --manifold asks Mesh_3 for a manifold surface
// (parameters::manifold()), not used by the race.
//
// Prints one line of JSON: seconds to read, to build the domain, of
// make_mesh_3 alone, to extract facets, to write, in total; triangles,
// vertices, peak RSS (getrusage). --diagnose also counts, after the timings
// (but within the process's wall time, so not for timed runs), the facets
// between differently labelled cells that are not on the surface.
//
// This program is benchmark-only: it is not part of the voronoimesh build and
// the library never depends on CGAL.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Image_3.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/make_mesh_3.h>

#ifdef CGAL_CONCURRENT_MESH_3
#include <tbb/global_control.h>
#include <tbb/info.h>
#endif

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Domain = CGAL::Labeled_mesh_domain_3<K>;
#ifdef CGAL_CONCURRENT_MESH_3
using Concurrency = CGAL::Parallel_tag; // needs CGAL_LINKED_WITH_TBB (CMakeLists.txt)
constexpr const char* kConcurrency = "parallel";
#else
using Concurrency = CGAL::Sequential_tag;
constexpr const char* kConcurrency = "sequential";
#endif
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, Concurrency>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct Options {
  std::string in, out;
  double facet_size = 2, facet_distance = 0.5, facet_angle = 30, cell_ratio = 3;
  int threads = 0; // 0: TBB's default (every core)
  bool optimise = false, manifold = false, diagnose = false;
  unsigned seed = 0;
};

[[noreturn]] void usage(const char* why) {
  std::fprintf(stderr,
               "cgal_label_mesher: %s\nusage: cgal_label_mesher IN.inr[.gz] OUT.ply [--facet-size V] "
               "[--facet-distance V] [--facet-angle DEG] [--cell-ratio R] [--threads N] [--optimise] "
               "[--manifold] [--seed S] [--diagnose]\n",
               why);
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  std::vector<std::string> pos;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> double {
      if (i + 1 >= argc) usage(("missing value after " + a).c_str());
      char* end = nullptr;
      const double v = std::strtod(argv[++i], &end);
      if (!end || *end) usage(("bad number for " + a).c_str());
      return v;
    };
    if (a == "--facet-size") o.facet_size = value();
    else if (a == "--facet-distance") o.facet_distance = value();
    else if (a == "--facet-angle") o.facet_angle = value();
    else if (a == "--cell-ratio") o.cell_ratio = value();
    else if (a == "--threads") o.threads = int(value());
    else if (a == "--seed") o.seed = unsigned(value());
    else if (a == "--optimise") o.optimise = true;
    else if (a == "--manifold") o.manifold = true;
    else if (a == "--diagnose") o.diagnose = true;
    else if (a.rfind("--", 0) == 0) usage(("unknown option " + a).c_str());
    else pos.push_back(a);
  }
  if (pos.size() != 2) usage("need IN and OUT");
  if (!(o.facet_size > 0 && o.facet_distance > 0 && o.facet_angle > 0 && o.facet_angle <= 30 && o.cell_ratio >= 2))
    usage("sizes must be > 0, the angle in (0, 30] (CGAL's bound for termination), the ratio >= 2");
  o.in = pos[0];
  o.out = pos[1];
  return o;
}

/// Every distinct voxel value, so the PLY names every label of the input, also
/// one CGAL's mesh may have lost (a phase with no triangles shows in `stats`).
std::set<int64_t> image_labels(const CGAL::Image_3& im) {
  const _image* p = im.image();
  const size_t n = size_t(p->xdim) * p->ydim * p->zdim;
  std::set<int64_t> labels;
  auto scan = [&](auto* data) {
    // A flag per value would need the range first; runs of equal voxels make
    // this cheap enough (one set insert per change of value).
    int64_t last = int64_t(data[0]);
    labels.insert(last);
    for (size_t i = 1; i < n; ++i)
      if (int64_t(data[i]) != last) labels.insert(last = int64_t(data[i]));
  };
  if (p->wordKind != WK_FIXED || p->vdim != 1) usage("the image must be one integer label per voxel");
  const bool sign = p->sign == SGN_SIGNED;
  switch (p->wdim) {
  case 1: sign ? scan(static_cast<const int8_t*>(p->data)) : scan(static_cast<const uint8_t*>(p->data)); break;
  case 2: sign ? scan(static_cast<const int16_t*>(p->data)) : scan(static_cast<const uint16_t*>(p->data)); break;
  case 4: sign ? scan(static_cast<const int32_t*>(p->data)) : scan(static_cast<const uint32_t*>(p->data)); break;
  default: usage("unsupported voxel size");
  }
  return labels;
}

/// The surface as voronoimesh's NodeMesh holds it: shared vertices, and per
/// triangle its two labels, phase0 < phase1, oriented from phase0 into phase1.
struct Surface {
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<int32_t, 3>> triangles;
  std::vector<std::array<int32_t, 2>> pairs;
  size_t same_label = 0; ///< facets in the complex with one label on both sides (skipped; should be 0)
};

/// Every facet of the complex's boundary (c3t3.facets_in_complex: the facets
/// between two different subdomains, or a subdomain and the outside), with the
/// labels of its two cells: a cell outside the complex is label 0, the outside
/// (create_labeled_image_mesh_domain's value_outside, and the null subdomain).
Surface extract(const C3t3& c3t3) {
  const Tr& tr = c3t3.triangulation();
  Surface s;
  std::unordered_map<const void*, int32_t> index; // vertex -> PLY index, so surfaces share vertices
  auto vertex = [&](Tr::Vertex_handle v) {
    auto [it, added] = index.emplace(&*v, int32_t(s.points.size()));
    if (added) {
      const auto& p = tr.geom_traits().construct_point_3_object()(v->point()); // drop the weight
      s.points.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
    }
    return it->second;
  };
  auto label = [&](Tr::Cell_handle c) -> int32_t {
    return c3t3.is_in_complex(c) ? int32_t(c3t3.subdomain_index(c)) : 0;
  };
  for (auto f = c3t3.facets_in_complex_begin(); f != c3t3.facets_in_complex_end(); ++f) {
    Tr::Cell_handle c = f->first;
    int i = f->second;
    // Orient from the finite cell: its opposite vertex is a real point.
    if (tr.is_infinite(c->vertex(i))) {
      const auto m = tr.mirror_facet(*f);
      c = m.first;
      i = m.second;
    }
    const Tr::Cell_handle other = c->neighbor(i);
    const int32_t inside = label(c), outside = label(other);
    if (inside == outside) {
      ++s.same_label;
      continue;
    }
    std::array<Tr::Vertex_handle, 3> v{c->vertex((i + 1) & 3), c->vertex((i + 2) & 3), c->vertex((i + 3) & 3)};
    auto pt = [&](Tr::Vertex_handle h) { return tr.geom_traits().construct_point_3_object()(h->point()); };
    // The normal (b-a)x(c-a) points towards the side of d iff POSITIVE (exact
    // predicate). We want it to point from the smaller label into the larger.
    const bool towards_c = CGAL::orientation(pt(v[0]), pt(v[1]), pt(v[2]), pt(c->vertex(i))) == CGAL::POSITIVE;
    const bool towards_larger = towards_c == (inside > outside);
    if (!towards_larger) std::swap(v[1], v[2]);
    s.triangles.push_back({vertex(v[0]), vertex(v[1]), vertex(v[2])});
    s.pairs.push_back({std::min(inside, outside), std::max(inside, outside)});
  }
  return s;
}

/// A diagnostic, not timed: facets between cells of different labels that are
/// not in the complex. The complex's surface is the restricted Delaunay
/// triangulation (facets whose dual Voronoi edge crosses the surface), not
/// the boundary of the labelled cells; where the two disagree, the boundary of
/// the cells has facets the surface lacks (and the surface is then not the
/// boundary of the subdomains its cells say).
size_t label_changes_off_surface(const C3t3& c3t3) {
  const Tr& tr = c3t3.triangulation();
  auto label = [&](Tr::Cell_handle c) -> int { return c3t3.is_in_complex(c) ? int(c3t3.subdomain_index(c)) : 0; };
  size_t n = 0;
  for (auto f = tr.finite_facets_begin(); f != tr.finite_facets_end(); ++f)
    if (!c3t3.is_in_complex(*f) && label(f->first) != label(f->first->neighbor(f->second))) ++n;
  return n;
}

template <class T>
void put(std::string& b, T v) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &v, sizeof(T)); // little-endian host (x86-64), as the header says
  b.append(bytes, sizeof(T));
}

/// voronoimesh's PLY (io/ply.cpp, read by io/ply_read.cpp): binary LE, double
/// vertices, faces with int phase0 < phase1 (labels); "comment domain" and a
/// "comment phase <label> <name>" per label, named as voronoimesh names the
/// phases of a label volume (background for 0, label<L> for the others).
/// The domain written is CGAL's own bounding box of the image, which is one
/// voxel larger than the image on every side: no vertex lies on it, so
/// `stats` holds every phase's boundary to being closed, as CGAL's surfaces
/// against label 0 should be.
void write_ply(const std::string& path, const Surface& s, const std::set<int64_t>& labels, const CGAL::Bbox_3& box) {
  std::string h = "ply\nformat binary_little_endian 1.0\n";
  h += "comment cgal_label_mesher (CGAL " CGAL_VERSION_STR " Mesh_3): normals point from phase0 into phase1\n";
  char buf[512];
  std::snprintf(buf, sizeof buf, "comment domain %.17g %.17g %.17g %.17g %.17g %.17g\n", box.xmin(), box.ymin(),
                box.zmin(), box.xmax(), box.ymax(), box.zmax());
  h += buf;
  std::set<int64_t> all = labels;
  all.insert(0); // the outside, whether or not the image has voxels of 0
  for (int64_t l : all) h += "comment phase " + std::to_string(l) + (l == 0 ? " background\n" : " label" + std::to_string(l) + "\n");
  h += "element vertex " + std::to_string(s.points.size()) + "\n";
  h += "property double x\nproperty double y\nproperty double z\n";
  h += "element face " + std::to_string(s.triangles.size()) + "\n";
  h += "property list uchar int vertex_indices\nproperty int phase0\nproperty int phase1\nend_header\n";
  std::string b = h;
  b.reserve(h.size() + s.points.size() * 24 + s.triangles.size() * 21);
  for (const auto& p : s.points)
    for (double x : p) put(b, x);
  for (size_t t = 0; t < s.triangles.size(); ++t) {
    b += char(3);
    for (int32_t v : s.triangles[t]) put(b, v);
    put(b, s.pairs[t][0]);
    put(b, s.pairs[t][1]);
  }
  std::ofstream f(path, std::ios::binary);
  f.write(b.data(), std::streamsize(b.size()));
  if (!f) {
    std::fprintf(stderr, "cgal_label_mesher: cannot write %s\n", path.c_str());
    std::exit(3);
  }
}

} // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const auto t_start = Clock::now();

#ifdef CGAL_CONCURRENT_MESH_3
  const int threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
#else
  const int threads = 1;
  if (o.threads > 1) usage("built without TBB: --threads must be 1");
#endif

  auto t = Clock::now();
  CGAL::Image_3 image;
  if (!image.read(o.in.c_str())) {
    std::fprintf(stderr, "cgal_label_mesher: cannot read %s\n", o.in.c_str());
    return 3;
  }
  const std::set<int64_t> labels = image_labels(image);
  const double read_s = seconds_since(t);
  const double voxel = std::min({image.vx(), image.vy(), image.vz()});

  t = Clock::now();
  CGAL::Random rng(o.seed);
  namespace p = CGAL::parameters;
  Domain domain = Domain::create_labeled_image_mesh_domain(image, p::p_rng = &rng);
  const double domain_s = seconds_since(t);
  Criteria criteria(p::facet_angle = o.facet_angle, p::facet_size = o.facet_size * voxel,
                    p::facet_distance = o.facet_distance * voxel, p::cell_radius_edge_ratio = o.cell_ratio);

  t = Clock::now();
  const auto manifold = o.manifold ? p::manifold() : p::non_manifold();
  C3t3 c3t3 = o.optimise ? CGAL::make_mesh_3<C3t3>(domain, criteria, manifold)
                         : CGAL::make_mesh_3<C3t3>(domain, criteria, p::no_perturb(), p::no_exude(), manifold);
  const double mesh_s = seconds_since(t);

  t = Clock::now();
  const Surface s = extract(c3t3);
  const double extract_s = seconds_since(t);

  t = Clock::now();
  const CGAL::Bbox_3 box(image.tx() - 1, image.ty() - 1, image.tz() - 1, image.xdim() * image.vx() + image.tx() + 1,
                         image.ydim() * image.vy() + image.ty() + 1, image.zdim() * image.vz() + image.tz() + 1);
  write_ply(o.out, s, labels, box);
  const double write_s = seconds_since(t);

  const double diagnostics_at = seconds_since(t_start);
  const long long off_surface = o.diagnose ? (long long)label_changes_off_surface(c3t3) : -1; // -1: not counted
  size_t outside = 0;
  for (const auto& pr : s.pairs) outside += pr[0] == 0;
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  std::printf("{\"tool\": \"cgal\", \"cgal\": \"%s\", \"input\": \"%s\", \"concurrency\": \"%s\", \"threads\": %d, "
              "\"voxel\": %.6g, \"facet_size\": %g, \"facet_distance\": %g, \"facet_angle\": %g, \"optimise\": %s, "
              "\"manifold\": %s, \"read_s\": %.3f, \"domain_s\": %.3f, \"make_mesh_3_s\": %.3f, \"extract_s\": %.3f, "
              "\"write_s\": %.3f, \"total_s\": %.3f, \"triangles\": %zu, \"triangles_against_0\": %zu, "
              "\"vertices\": %zu, \"c3t3_vertices\": %zu, \"cells_in_complex\": %zu, \"same_label_facets\": %zu, "
              "\"label_changes_off_surface\": %lld, \"labels\": %zu, \"peak_rss_mib\": %.1f}\n",
              CGAL_VERSION_STR, o.in.c_str(), kConcurrency, threads, voxel, o.facet_size, o.facet_distance,
              o.facet_angle, o.optimise ? "true" : "false", o.manifold ? "true" : "false", read_s, domain_s, mesh_s,
              extract_s, write_s, diagnostics_at, s.triangles.size(), outside, s.points.size(),
              size_t(c3t3.triangulation().number_of_vertices()), size_t(c3t3.number_of_cells_in_complex()),
              s.same_label, off_surface, labels.size(), double(ru.ru_maxrss) / 1024.0);
  return 0;
}
