#include <mechgraph/host/angle_reference.hpp>

namespace mechgraph::host {

std::string angle_reference(const NodeInfo& info, const std::string& frame_id, const Dimension& d) {
  if (d.angle == 0) return {};
  const AngleFrame* frame = info.find_frame(frame_id);
  return frame ? frame->unit_tag : std::string();
}

std::string column_angle_reference(const NodeInfo& info, const PortSpec& port, const std::string& name, const Dimension& d) {
  const ChannelDecl* decl = port.presentation.find(name);
  return decl ? angle_reference(info, decl->angle_frame, d) : std::string();
}

std::string unit_with_reference(const std::string& unit, const std::string& reference) {
  if (reference.empty() || unit.find("deg") == std::string::npos) return unit;
  return unit + " (" + reference + ")";
}

std::string unit_without_reference(const std::string& unit) {
  const std::size_t open = unit.rfind(" (");
  if (open == std::string::npos || unit.empty() || unit.back() != ')' || unit.find("deg") >= open) return unit;
  return unit.substr(0, open);
}

}  // namespace mechgraph::host
