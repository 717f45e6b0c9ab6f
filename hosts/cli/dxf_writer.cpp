#include "dxf_writer.hpp"

#include <mechgraph/errors.hpp>

#include <dxflib/dl_dxf.h>

#include <algorithm>
#include <cctype>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace mechgraph::cli {
namespace {

struct Curve {
  std::string layer;
  const std::vector<double>* x = nullptr;
  const std::vector<double>* y = nullptr;
};

// The x/y channel pairs of a table: "x"/"y" on CONTOUR, "p_x"/"p_y" on layer P (capitals).
std::vector<Curve> curves_of(const Table& t) {
  std::vector<Curve> out;
  for (const Table::Column& c : t.channels) {
    if (c.dimension != dim::length) continue;
    const std::string& n = c.name;
    std::string prefix;
    if (n == "x") prefix = "";
    else if (n.size() > 2 && n.compare(n.size() - 2, 2, "_x") == 0) prefix = n.substr(0, n.size() - 2);
    else continue;
    const Table::Column* y = t.find(prefix.empty() ? "y" : prefix + "_y");
    if (!y || y->dimension != dim::length) continue;
    std::string layer = prefix.empty() ? "CONTOUR" : prefix;
    std::transform(layer.begin(), layer.end(), layer.begin(), [](unsigned char ch) { return std::toupper(ch); });
    out.push_back({layer, &c.values, &y->values});
  }
  return out;
}

}  // namespace

bool is_drawable_curve(const Table& t) { return t.closed_curve && !curves_of(t).empty(); }

void write_dxf(const std::filesystem::path& file, const Table& t) {
  const std::vector<Curve> curves = curves_of(t);
  DL_Dxf dxf;
  std::unique_ptr<DL_WriterA> dw(dxf.out(file.c_str(), DL_Codes::AC1015));
  if (!dw || dw->openFailed()) throw IoError("cannot write '" + file.string() + "'");

  dxf.writeHeader(*dw);
  dw->dxfString(9, "$INSUNITS");
  dw->dxfInt(70, 4);  // millimetres
  dw->sectionEnd();

  dw->sectionTables();
  dxf.writeVPort(*dw);
  dw->tableLinetypes(3);
  dxf.writeLinetype(*dw, DL_LinetypeData("BYBLOCK", "", 0, 0, 0.0));
  dxf.writeLinetype(*dw, DL_LinetypeData("BYLAYER", "", 0, 0, 0.0));
  dxf.writeLinetype(*dw, DL_LinetypeData("CONTINUOUS", "Solid line", 0, 0, 0.0));
  dw->tableEnd();
  dw->tableLayers(static_cast<int>(curves.size()) + 1);
  dxf.writeLayer(*dw, DL_LayerData("0", 0), DL_Attributes("", DL_Codes::black, 100, "CONTINUOUS", 1.0));
  int colour = DL_Codes::red;
  for (const Curve& c : curves)
    dxf.writeLayer(*dw, DL_LayerData(c.layer, 0), DL_Attributes("", colour++, 100, "CONTINUOUS", 1.0));
  dw->tableEnd();
  dw->tableStyle(1);
  dxf.writeStyle(*dw, DL_StyleData("standard", 0, 2.5, 1.0, 0.0, 0, 2.5, "txt", ""));
  dw->tableEnd();
  dxf.writeView(*dw);
  dxf.writeUcs(*dw);
  dw->tableAppid(1);
  dxf.writeAppid(*dw, "ACAD");
  dw->tableEnd();
  dxf.writeDimStyle(*dw, 1, 1, 1, 1, 1);
  dxf.writeBlockRecord(*dw);
  dw->tableEnd();
  dw->sectionEnd();

  dw->sectionBlocks();
  for (const char* block : {"*Model_Space", "*Paper_Space", "*Paper_Space0"}) {
    dxf.writeBlock(*dw, DL_BlockData(block, 0, 0.0, 0.0, 0.0));
    dxf.writeEndBlock(*dw, block);
  }
  dw->sectionEnd();

  dw->sectionEntities();
  for (const Curve& c : curves) {
    const DL_Attributes on_layer(c.layer, 256, -1, "BYLAYER", 1.0);
    dxf.writePolyline(*dw, DL_PolylineData(static_cast<int>(c.x->size()), 0, 0, 1 /* closed */), on_layer);
    for (std::size_t i = 0; i < c.x->size(); ++i) dxf.writeVertex(*dw, DL_VertexData((*c.x)[i] * 1e3, (*c.y)[i] * 1e3, 0.0));
    dxf.writePolylineEnd(*dw);
  }
  dw->sectionEnd();
  dxf.writeObjects(*dw);
  dxf.writeObjectsEnd(*dw);
  dw->dxfEOF();
  dw->close();
  std::error_code ec;
  if (!std::filesystem::exists(file, ec) || std::filesystem::file_size(file, ec) == 0)
    throw IoError("cannot write '" + file.string() + "'");
}

}  // namespace mechgraph::cli
