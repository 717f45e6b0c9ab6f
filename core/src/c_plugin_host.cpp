#include "c_plugin_host.hpp"

#include "c_node_type.hpp"

#include <spdlog/spdlog.h>

#include <cstdlib>
#include <cstring>
#include <new>
#include <string_view>

namespace mechgraph::detail {
namespace {

void log_message(int32_t level, const char* plugin_id, mg_str message) {
  try {
    const std::string_view text(message.data ? message.data : "", message.data ? message.size : 0);
    const char* id = plugin_id ? plugin_id : "?";
    if (level <= MG_LOG_DEBUG) spdlog::debug("[{}] {}", id, text);
    else if (level == MG_LOG_INFO) spdlog::info("[{}] {}", id, text);
    else spdlog::warn("[{}] {}", id, text);
  } catch (...) {  // a logger that cannot log loses the line, never the process
  }
}

// Host-owned buffers: aligned_alloc wants a size that is a multiple of the alignment.
void* memory_alloc(size_t bytes, size_t align) {
  if (align < alignof(std::max_align_t)) align = alignof(std::max_align_t);
  if ((align & (align - 1)) != 0) return nullptr;
  const size_t rounded = (bytes + align - 1) / align * align;
  if (rounded < bytes) return nullptr;
  return std::aligned_alloc(align, rounded == 0 ? align : rounded);
}
void memory_free(void* p) { std::free(p); }
void release_host_buffer(void* p) { std::free(p); }
mg_owner memory_owner_of(void* p) { return mg_owner{p, &release_host_buffer}; }

const mg_log_suite_v1 log_suite{sizeof(mg_log_suite_v1), &log_message};
const mg_memory_suite_v1 memory_suite{sizeof(mg_memory_suite_v1), &memory_alloc, &memory_free, &memory_owner_of};

const void* fetch_suite(void*, const char* name, uint32_t version) {
  if (!name) return nullptr;
  if (std::strcmp(name, MG_SUITE_LOG) == 0 && version == 1) return &log_suite;
  if (std::strcmp(name, MG_SUITE_EVAL) == 0 && version == 1) return &c_eval_suite();
  if (std::strcmp(name, MG_SUITE_MEMORY) == 0 && version == 1) return &memory_suite;
  return nullptr;
}

}  // namespace

const mg_host& c_plugin_host() {
  static const mg_host host{sizeof(mg_host), MG_SDK_MAJOR, MG_SDK_MINOR, "mechgraph " MECHGRAPH_VERSION, nullptr, &fetch_suite};
  return host;
}

}  // namespace mechgraph::detail
