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

}  // namespace mechgraph::host
