#include "dxf_writer.hpp"

#include "output_file.hpp"

#include <mechgraph/errors.hpp>

#include <dxflib/dl_dxf.h>
#include <dxflib/dl_writer_ascii.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mechgraph::cli {
namespace {

struct Curve {
  std::string layer;
  const std::vector<double>* x = nullptr;
  const std::vector<double>* y = nullptr;
  bool closed = true;  // a part shown at rest (stroke 2) is drawn as its path goes
};

// Every text of the drawing goes through here: a DXF file is a list of group-code/value lines, so
// a line break in a plugin's channel name would start groups of its own (a forged entity). Control
// characters become '_'.
std::string dxf_text(std::string_view text) {
  std::string out(text);
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '_';
  return out;
}

// A layer name from a channel prefix: capitals, and '_' for what DXF symbol table names may not
// hold (< > / \ " : ; ? * | = ' and control characters).
std::string dxf_layer_name(std::string_view prefix) {
  std::string layer = dxf_text(prefix);
  for (char& c : layer) {
    c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (std::string_view("<>/\\\":;?*|='").find(c) != std::string_view::npos) c = '_';
  }
  return layer.substr(0, 255);
}

// The x/y channel pairs the table's presentation declares (drawing_to_scale), each on its layer
// (capitals); pairs whose channels the table lacks or that are not lengths are left out.
std::vector<Curve> curves_of(const Table& t, const Presentation& presentation) {
  std::vector<Curve> out;
  if (presentation.role != Role::drawing_to_scale) return out;
  for (const XyPair& pair : presentation.pairs) {
    const Table::Column* x = t.find(pair.x);
    const Table::Column* y = t.find(pair.y);
    if (!x || !y || x->dimension != dim::length || y->dimension != dim::length) continue;
    out.push_back({dxf_layer_name(pair.layer), &x->values, &y->values, pair.stroke != 2});
  }
  return out;
}

// dxflib's own writer streams to a file it opens and keeps the stream to itself, so a full disk
// goes unnoticed. This one keeps dxflib's group-code layout but collects the text in memory; the
// caller writes it with every write checked. (DL_Dxf takes a DL_WriterA, hence the base: given no
// file name its stream opens nothing and is never used, every output call is overridden here.)
class BufferWriter final : public DL_WriterA {
 public:
  BufferWriter() : DL_WriterA("", DL_Codes::AC1015) {}
  const std::string& text() const { return text_; }

  void dxfReal(int gc, double value) const override {
    // Plain decimal notation (CAD readers do not all take exponents), shortest digits that keep
    // the value, without trailing zeros.
    char buffer[400];
    auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed);
    std::string digits = ec == std::errc() ? std::string(buffer, end) : std::string("0");
    if (digits.find('.') == std::string::npos) digits += ".0";
    dxfString(gc, digits);
  }
  void dxfInt(int gc, int value) const override { dxfString(gc, std::to_string(value)); }
  void dxfHex(int gc, int value) const override {
    char buffer[16];
    auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, static_cast<unsigned>(value), 16);
    std::string hex(buffer, ec == std::errc() ? end : buffer);
    std::transform(hex.begin(), hex.end(), hex.begin(), [](unsigned char c) { return std::toupper(c); });
    dxfString(gc, hex);
  }
  void dxfString(int gc, const char* value) const override { dxfString(gc, std::string(value ? value : "")); }
  void dxfString(int gc, const std::string& value) const override {
    // The group code right-aligned in three columns, then the value, each on its own line.
    const std::string code = std::to_string(gc);
    if (code.size() < 3) text_.append(3 - code.size(), ' ');
    text_ += code;
    text_ += '\n';
    text_ += dxf_text(value);
    text_ += '\n';
  }

 private:
  mutable std::string text_;
};

}  // namespace

bool is_drawable_curve(const Table& t, const Presentation& presentation) {
  return t.closed_curve && !curves_of(t, presentation).empty();
}

void write_dxf(const std::filesystem::path& file, const Table& t, const Presentation& presentation,
               const std::vector<std::string>& notes) {
  const std::vector<Curve> curves = curves_of(t, presentation);
  DL_Dxf dxf;
  auto dw = std::make_unique<BufferWriter>();

  // The node's notes (a drawing's direction of rotation) as comments, escaped like every text.
  for (const std::string& n : notes) dw->dxfString(999, dxf_text(n));

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
    dxf.writePolyline(*dw, DL_PolylineData(static_cast<int>(c.x->size()), 0, 0, c.closed ? 1 : 0), on_layer);
    for (std::size_t i = 0; i < c.x->size(); ++i) dxf.writeVertex(*dw, DL_VertexData((*c.x)[i] * 1e3, (*c.y)[i] * 1e3, 0.0));
    dxf.writePolylineEnd(*dw);
  }
  dw->sectionEnd();
  dxf.writeObjects(*dw);
  dxf.writeObjectsEnd(*dw);
  dw->dxfEOF();
  // Whole or not at all, every write, fsync and close checked (a full disk is IoError, exit 5).
  write_file_whole(file, false, [&](std::ostream& os) { os << dw->text(); });
}

}  // namespace mechgraph::cli
