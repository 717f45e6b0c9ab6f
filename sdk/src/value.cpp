#include <mechgraph/value.hpp>

namespace mechgraph {

std::string_view to_string(ValueKind kind) {
  switch (kind) {
    case ValueKind::scalar: return "scalar";
    case ValueKind::series: return "series";
    case ValueKind::handle: return "handle";
    case ValueKind::table: return "table";
  }
  return "?";
}

}  // namespace mechgraph
