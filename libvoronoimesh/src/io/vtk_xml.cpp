/// @file io/vtk_xml.cpp
/// VTK XML datasets for ParaView and VTK: .vtu (UnstructuredGrid of triangles)
/// and .vtp (PolyData with polys), ASCII, with the phase pair of each triangle
/// as cell data and the junction order of each node as point data; and the
/// .pvtu index of such pieces, which names the same arrays.

#include "core/text.hpp"
#include "io/output_buffer.hpp"
#include "io/phase_names.hpp"
#include "io/writers.hpp"
#include "voronoimesh/mesh/junctions.hpp"

namespace vm::io::detail {

namespace {

using vm::detail::cat;
using vm::detail::ChunkedOutput;
using vm::detail::put_int;

// The data arrays of every dataset, named once for the pieces and their index.
constexpr const char* kNodeArray = "junction_order"; // Int32 point data
constexpr std::array<const char*, 2> kPhaseArrays{"phase0", "phase1"}; // Int32 cell data
constexpr const char* kColorTable = "phase_colors"; // Float64 field data: label, red, green, blue

/// `text` made safe inside an XML comment, which may not hold "--" or end in "-".
std::string xml_comment_safe(const std::string& text) {
  std::string s;
  for (char c : text) {
    if (c == '-' && !s.empty() && s.back() == '-') s += ' ';
    s += c;
  }
  if (!s.empty() && s.back() == '-') s += ' ';
  return s;
}

/// `text` made safe in an XML attribute value (in double quotes).
std::string xml_attribute_safe(const std::string& text) {
  std::string s;
  for (char c : text) {
    switch (c) {
    case '&': s += "&amp;"; break;
    case '<': s += "&lt;"; break;
    case '>': s += "&gt;"; break;
    case '"': s += "&quot;"; break;
    default: s += c;
    }
  }
  return s;
}

/// One ASCII DataArray of integers, `value(i)` for i in [0, n), 12 per line.
template <class Value>
void int_array(ChunkedOutput& out, const char* type, const char* name, size_t n, Value value) {
  std::string& buf = out.text();
  buf += cat("        <DataArray type=\"", type, "\" Name=\"", name, "\" format=\"ascii\">\n");
  for (size_t i = 0; i < n; ++i) {
    buf.append(i % 12 == 0 ? 10 : 1, ' ');
    put_int(buf, value(i));
    if (i % 12 == 11 || i + 1 == n) buf += '\n';
    out.maybe_flush();
  }
  buf += "        </DataArray>\n";
}

/// The FieldData element: the named phases, one Int32 array per phase named as
/// it is and holding its label (what ParaView lists and meshio reads as
/// field_data), and the colours in one table beside them, a row per coloured
/// phase keyed by label (an array per colour would read as one more named
/// phase). Empty when no phase has a name or a colour.
std::string field_data(const NodeMesh& m, size_t phases) {
  if (m.phase_names.empty() && !has_phase_colors(m)) return {};
  std::string buf = "    <FieldData>\n";
  for (size_t p = 0; p < phases; ++p)
    if (const std::string name = phase_name(m, int32_t(p)); !name.empty())
      buf += cat("      <DataArray type=\"Int32\" Name=\"", xml_attribute_safe(name),
                 "\" NumberOfTuples=\"1\" format=\"ascii\">", m.label_of(int32_t(p)), "</DataArray>\n");
  if (has_phase_colors(m)) {
    size_t rows = 0;
    for (size_t p = 0; p < phases; ++p) rows += phase_color(m, int32_t(p)).has_value();
    buf += cat("      <DataArray type=\"Float64\" Name=\"", kColorTable, "\" NumberOfComponents=\"4\"",
               " ComponentName0=\"label\" ComponentName1=\"red\" ComponentName2=\"green\"",
               " ComponentName3=\"blue\" NumberOfTuples=\"", rows, "\" format=\"ascii\">\n");
    for (size_t p = 0; p < phases; ++p)
      if (const auto color = phase_color(m, int32_t(p))) {
        buf += cat("        ", m.label_of(int32_t(p)), " ");
        vm::detail::put_color(buf, *color);
        buf += '\n';
      }
    buf += "      </DataArray>\n";
  }
  return buf + "    </FieldData>\n";
}

} // namespace

void write_vtk_xml(vm::detail::StagedOutputs& staged, const NodeMesh& m, const std::string& path,
                   VtkDataset dataset) {
  const Junctions junctions = find_junctions(m);
  const bool grid = dataset == VtkDataset::unstructured_grid;
  const char* const type = grid ? "UnstructuredGrid" : "PolyData";
  const char* const cells = grid ? "Cells" : "Polys";
  const size_t nt = m.triangles.size();
  vm::detail::write_in_chunks(staged, path, [&](ChunkedOutput& out) {
    std::string& buf = out.text();
    buf += "<?xml version=\"1.0\"?>\n<!-- voronoimesh interface mesh. Cell data phase0, phase1: the phase labels of"
           " each triangle, its normal pointing from phase0 into phase1. Point data junction_order: the number of"
           " phases meeting at the node (2 surface, 3 triple curve, 4 or more quadruple point). Phases:";
    const size_t phases = phase_count(m); // scans every triangle: once, not once per phase
    for (size_t p = 0; p < phases; ++p) buf += ' ' + xml_comment_safe(phase_token(m, int32_t(p)));
    buf += " -->\n";
    buf += cat("<VTKFile type=\"", type, "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n");
    buf += cat("  <", type, ">\n");
    buf += field_data(m, phases);
    buf += grid ? cat("    <Piece NumberOfPoints=\"", m.points.size(), "\" NumberOfCells=\"", nt, "\">\n")
                : cat("    <Piece NumberOfPoints=\"", m.points.size(),
                      "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"", nt, "\">\n");
    buf += cat("      <PointData Scalars=\"", kNodeArray, "\">\n");
    int_array(out, "Int32", kNodeArray, m.points.size(), [&](size_t n) { return junctions.order(n); });
    buf += cat("      </PointData>\n      <CellData Scalars=\"", kPhaseArrays[0], "\">\n");
    for (size_t k = 0; k < 2; ++k)
      int_array(out, "Int32", kPhaseArrays[k], nt, [&](size_t t) { return m.label_of(m.pairs[t][k]); });
    buf += "      </CellData>\n      <Points>\n"
           "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const Vec3& p : m.points) {
      buf += "          ";
      vm::detail::put_point(buf, p);
      buf += '\n';
      out.maybe_flush();
    }
    buf += "        </DataArray>\n      </Points>\n";
    buf += cat("      <", cells, ">\n");
    int_array(out, "Int64", "connectivity", 3 * nt, [&](size_t i) { return m.triangles[i / 3][i % 3]; });
    int_array(out, "Int64", "offsets", nt, [](size_t t) { return 3 * (int64_t(t) + 1); });
    if (grid) int_array(out, "UInt8", "types", nt, [](size_t) { return 5; }); // VTK_TRIANGLE
    buf += cat("      </", cells, ">\n");
    buf += cat("    </Piece>\n  </", type, ">\n</VTKFile>\n");
  });
}

void write_pvtu_index(vm::detail::StagedOutputs& staged, const std::string& path,
                      const std::vector<std::string>& pieces) {
  vm::detail::write_in_chunks(staged, path, [&](ChunkedOutput& out) {
    std::string& buf = out.text();
    buf += "<?xml version=\"1.0\"?>\n"
           "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
           "  <PUnstructuredGrid GhostLevel=\"0\">\n";
    buf += cat("    <PPointData Scalars=\"", kNodeArray, "\">\n");
    buf += cat("      <PDataArray type=\"Int32\" Name=\"", kNodeArray, "\"/>\n");
    buf += cat("    </PPointData>\n    <PCellData Scalars=\"", kPhaseArrays[0], "\">\n");
    for (const char* name : kPhaseArrays) buf += cat("      <PDataArray type=\"Int32\" Name=\"", name, "\"/>\n");
    buf += "    </PCellData>\n"
           "    <PPoints>\n"
           "      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n"
           "    </PPoints>\n";
    for (const std::string& piece : pieces) buf += cat("    <Piece Source=\"", piece, "\"/>\n");
    buf += "  </PUnstructuredGrid>\n</VTKFile>\n";
  });
}

} // namespace vm::io::detail
