#pragma once
// Whether a C++ NodeType has a forecast of its own (overrides NodeType::forecast), so that the C
// layer can declare that it has none: its node type then answers NULL when the host asks for
// mechgraph.node.forecast/1 (c/node_forecast.h), which a host of any 1.x reads as "count me by the
// conventions" once, when it loads the type, instead of asking through C for every case of a
// sweep and hearing MG_ERR_UNSUPPORTED each time. The answer is the same either way; only the
// cost differs.
//
// How: the plugin's compiler lays out vtables by the Itanium C++ ABI (the platforms of
// docs/writing-plugins.md: Linux on x86_64 and aarch64, gcc or clang). A pointer to the virtual
// member NodeType::forecast holds its vtable slot; a type that does not override it has, in that
// slot, what a type known not to override it has. The reading is checked once on two probe types
// (one that overrides, one that does not); if it does not tell them apart, every type counts as
// having a forecast (the answer through C every time, as before): never a forecast lost.
// Header-only and hidden, compiled into each plugin (export_node.hpp).
#include <mechgraph/node.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>

namespace mechgraph::detail {

namespace forecast_probe {

class __attribute__((visibility("hidden"))) Plain final : public NodeType {
 public:
  const NodeInfo& info() const override {
    static const NodeInfo none;
    return none;
  }
  void evaluate(const ParamSet&, const InputSet&, OutputSet&, EvalContext&) const override {}
};
class __attribute__((visibility("hidden"))) PlainToo final : public NodeType {
 public:
  const NodeInfo& info() const override {
    static const NodeInfo none;
    return none;
  }
  void evaluate(const ParamSet&, const InputSet&, OutputSet&, EvalContext&) const override {}
};
class __attribute__((visibility("hidden"))) Own final : public NodeType {
 public:
  const NodeInfo& info() const override {
    static const NodeInfo none;
    return none;
  }
  void evaluate(const ParamSet&, const InputSet&, OutputSet&, EvalContext&) const override {}
  std::optional<WorkForecast> forecast(const ParamSet&, const InputSizes&) const override { return WorkForecast{}; }
};

// The slot of NodeType::forecast in a NodeType's vtable (Itanium C++ ABI: a pointer to a virtual
// member is {1 + the slot's offset in bytes, this-adjustment}; the ARM variant, aarch64's, keeps
// the offset as it is and marks "virtual" in the adjustment's lowest bit). Empty when the pointer
// does not say virtual.
__attribute__((visibility("hidden"))) inline std::optional<std::size_t> slot() {
  using Forecast = std::optional<WorkForecast> (NodeType::*)(const ParamSet&, const InputSizes&) const;
  struct Representation {
    std::uintptr_t ptr;
    std::ptrdiff_t adj;
  };
  static_assert(sizeof(Forecast) == sizeof(Representation), "a pointer to member function of the Itanium C++ ABI");
  const Forecast member = &NodeType::forecast;
  Representation r;
  std::memcpy(&r, &member, sizeof r);
#if defined(__aarch64__) || defined(__arm__)
  if ((r.adj & 1) == 0) return std::nullopt;
  return r.ptr / sizeof(void*);
#else
  if ((r.ptr & 1) == 0) return std::nullopt;
  return (r.ptr - 1) / sizeof(void*);
#endif
}

// What `type`'s vtable holds in slot `i`.
__attribute__((visibility("hidden"))) inline const void* entry(const NodeType& type, std::size_t i) {
  const void* const* vtable;
  std::memcpy(&vtable, static_cast<const void*>(&type), sizeof vtable);  // the vtable pointer leads a polymorphic object
  return vtable[i];
}

// The slot and what a type without its own forecast holds there, once the probes agree.
struct Reading {
  std::size_t slot = 0;
  const void* inherited = nullptr;
  bool valid = false;
};
__attribute__((visibility("hidden"))) inline const Reading& reading() {
  static const Reading r = [] {
    Reading out;
    const std::optional<std::size_t> i = slot();
    if (!i) return out;
    static const Plain plain;
    static const PlainToo plain_too;
    static const Own own;
    const void* inherited = entry(plain, *i);
    if (!inherited || entry(plain_too, *i) != inherited || entry(own, *i) == inherited) return out;
    return Reading{*i, inherited, true};
  }();
  return r;
}

}  // namespace forecast_probe

/// Whether `type` overrides NodeType::forecast; true when that cannot be read (see above).
__attribute__((visibility("hidden"))) inline bool has_own_forecast(const NodeType& type) {
  const forecast_probe::Reading& r = forecast_probe::reading();
  return !r.valid || forecast_probe::entry(type, r.slot) != r.inherited;
}

}  // namespace mechgraph::detail
