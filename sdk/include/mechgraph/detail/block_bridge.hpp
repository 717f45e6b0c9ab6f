#pragma once
// Blocks of domain objects across the SDK 1.x C boundary (c/node_block.h, mg_object_block),
// header-only and hidden like object_bridge.hpp: the plugin's side (export_block.hpp) and the
// host's (core/src/c_block_node_type.cpp) both convert with it.
//
//  - export_block: a C++ DomainBlock as an mg_object_block that owns what it points to (the C++
//    block kept alive for the laws and the figures' arrays), released once by its owner. A
//    CamLawBlock crosses as its laws; a ValveMotionBlock as its cases' cam laws and the five
//    figures of c/domain/valve_motion_block.h, which point into the C++ block (no copy). The laws
//    live in one array of the block (BlockLaw, object_bridge.hpp): one allocation per block, not
//    one per case, and a reference to a law is a reference to the block.
//  - import_block: the C++ block of an mg_object_block (borrowed), for a port of an SDK kind: the
//    very C++ block when this library made it, or a library of this one's C++ layer did
//    (mechgraph.object.cxx/1, c/object_cxx.h); else each object imported as import_object does
//    (this library's own unwrapped, another's a Foreign view holding its own reference), the
//    figures copied.
// Other kinds have no block form: export_block and import_block refuse them (std::invalid_argument),
// so the node's block fails and every case runs alone.
#include <mechgraph/block.hpp>
#include <mechgraph/c/domain/valve_motion_block.h>
#include <mechgraph/c/node_block.h>
#include <mechgraph/detail/object_bridge.hpp>
#include <mechgraph/domain/cam_law_block.hpp>
#include <mechgraph/domain/valve_motion_block.hpp>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph::detail {

/// The objects of a block of laws: one per case, or one when every case holds the same law. A law
/// made here becomes a BlockLaw in the block's one array (object_bridge.hpp); the view of a
/// foreign law is passed on as its original object (one reference held by the block).
template <class LawOfCase>
void export_laws(ExportedBlock& e, std::size_t n, LawOfCase law_of_case) {
  bool shared = true;
  for (std::size_t i = 1; i < n && shared; ++i) shared = law_of_case(i).get() == law_of_case(0).get();
  const std::size_t count = shared ? std::min<std::size_t>(n, 1) : n;
  e.objects.reserve(count);
  e.laws.reserve(count);  // the laws' addresses cross: never reallocated after this
  for (std::size_t i = 0; i < count; ++i) {
    const std::shared_ptr<const CamLaw>& law = law_of_case(i);
    if (!law) {
      e.objects.push_back(nullptr);  // a failed case
      continue;
    }
    // The address of the type's typeinfo, as export_cam_law tells a view of a foreign law.
    const CamLaw& object = *law;
    if (&typeid(object) == &typeid(ForeignCamLaw)) {
      const mg_object* original = static_cast<const ForeignCamLaw&>(object).c_object();
      e.passed_on.push_back(original);
      original->vtbl->retain(original);
      e.objects.push_back(original);
      continue;
    }
    BlockLaw& made = e.laws.emplace_back();
    made.vtbl = &block_law_vtbl;
    made.primary = law.get();
    made.block = &e;
    made.self = law;
    e.objects.push_back(&made);
  }
}

/// `block` (the output or input of a node) as C, owning what it points to; `maker` names the node
/// type for messages. Throws std::invalid_argument for a kind without a block form.
inline mg_object_block export_block(const std::shared_ptr<const DomainBlock>& block, std::string_view maker) {
  if (!block) throw std::invalid_argument("an empty block of domain objects cannot cross the C boundary");
  auto e = std::make_unique<ExportedBlock>();
  e->keep = block;
  e->maker = maker;
  const std::size_t n = block->size();
  if (const auto* laws = dynamic_cast<const CamLawBlock*>(block.get())) {
    export_laws(*e, n, [laws](std::size_t i) -> const std::shared_ptr<const CamLaw>& { return laws->shared(i); });
  } else if (const auto* motions = dynamic_cast<const ValveMotionBlock*>(block.get())) {
    export_laws(*e, n, [motions](std::size_t i) -> const std::shared_ptr<const CamLaw>& { return motions->shared_cam(i); });
    const std::size_t stride = n == 1 ? 0 : 1;
    e->figures.resize(MG_VALVE_MOTION_BLOCK_FIGURES);
    e->figures[MG_VALVE_MOTION_BLOCK_OPEN_BEGIN] = {motions->open_begin.data(), stride};
    e->figures[MG_VALVE_MOTION_BLOCK_OPEN_END] = {motions->open_end.data(), stride};
    e->figures[MG_VALVE_MOTION_BLOCK_ROCKER_RATIO] = {motions->rocker_ratio.data(), stride};
    e->figures[MG_VALVE_MOTION_BLOCK_LASH] = {motions->lash.data(), stride};
    e->figures[MG_VALVE_MOTION_BLOCK_CAMSHAFT_SPEED] = {motions->camshaft_speed.data(), stride};
  } else {
    throw std::invalid_argument("a block of '" + std::string(block->kind()) + "' has no C form (c/node_block.h)");
  }
  mg_object_block out{sizeof(mg_object_block), e->objects.size(), e->objects.data(), e->figures.data(), e->figures.size(),
                      {e.get(), &ExportedBlock::release}, &object_origin};
  e.release();
  return out;
}

/// Laws the importer already holds a view of: the laws of a block it passed in (its C objects
/// and its C++ block, a CamLawBlock or a ValveMotionBlock), which come back in the blocks it gets
/// out (a valve motion block's cams) and need no second view.
struct KnownLaws {
  const mg_object* const* objects = nullptr;
  std::size_t count = 0;
  const DomainBlock* block = nullptr;
  // Case i's law when the C object `o` is the one passed in for it, else nullptr.
  std::shared_ptr<const CamLaw> find(std::size_t i, const mg_object* o) const {
    if (!objects || count == 0) return nullptr;
    const std::size_t j = count == 1 ? 0 : i;
    if (j >= count || objects[j] != o) return nullptr;
    if (const auto* laws = dynamic_cast<const CamLawBlock*>(block)) return laws->shared(j);
    if (const auto* motions = dynamic_cast<const ValveMotionBlock*>(block)) return motions->shared_cam(j);
    return nullptr;
  }
};

/// The laws of `in` (borrowed) as a CamLawBlock; `what` names the block in messages.
inline std::shared_ptr<const CamLawBlock> import_laws(const mg_object_block& in, std::size_t cases, const std::string& what,
                                                      const KnownLaws& known = {}) {
  if (in.object_count != 1 && in.object_count != cases)
    throw std::invalid_argument(what + " holds " + std::to_string(in.object_count) + " objects for a block of " + std::to_string(cases) +
                                " cases");
  if (!in.objects) throw std::invalid_argument(what + " has no array of objects");
  std::vector<std::shared_ptr<const CamLaw>> laws(in.object_count);
  for (std::size_t i = 0; i < in.object_count; ++i) {
    if (!in.objects[i]) continue;  // a failed case
    if ((laws[i] = known.find(i, in.objects[i]))) continue;
    laws[i] = import_cam_law(in.objects[i]);
    if (!laws[i]) throw std::invalid_argument(what + ": object " + std::to_string(i) + " is no cam law");
  }
  return std::make_shared<const CamLawBlock>(std::move(laws));
}

/// The C++ block behind `in` (borrowed) when a library of this one's C++ layer made it (its first
/// object answers mechgraph.object.cxx/1 with this library's key, and that library owns the block),
/// else nullptr.
inline std::shared_ptr<const DomainBlock> same_cxx_block(const mg_object_block& in) {
  if (!in.objects) return nullptr;
  for (std::size_t i = 0; i < in.object_count; ++i)
    if (const mg_object* o = in.objects[i]) {
      const mg_object_cxx_v1* t = same_cxx(o);
      const void* shared = t ? t->shared_block(&in) : nullptr;
      return shared ? *static_cast<const std::shared_ptr<const DomainBlock>*>(shared) : nullptr;
    }
  return nullptr;
}

/// The C++ block of `in` (borrowed) for a port of kind `kind` in a block of `cases` cases: the very
/// C++ block when this library exported it, else a view of its objects and a copy of its figures.
inline std::shared_ptr<const DomainBlock> import_block(const mg_object_block& in, std::string_view kind, std::size_t cases,
                                                       const std::string& what, const KnownLaws& known = {}) {
  if (in.struct_size < sizeof(mg_object_block)) throw std::invalid_argument(what + " is a malformed mg_object_block (struct_size)");
  if (in.origin == &object_origin && in.owner.ctx && in.owner.release == &ExportedBlock::release)
    return static_cast<const ExportedBlock*>(in.owner.ctx)->keep;  // made here: no C hop
  if (auto same = same_cxx_block(in); same && same->kind() == kind && (same->size() == cases || (same->size() == 1 && in.object_count == 1)))
    return same;  // made by a library of this one's C++ layer: no C hop
  const SdkInterface* sdk = sdk_interface_of_kind(kind);
  const std::size_t position = sdk ? static_cast<std::size_t>(sdk - sdk_interfaces) : SIZE_MAX;
  if (position == 0) return import_laws(in, cases, what, known);  // mechgraph.cam_law
  if (position == 1) {                                     // mechgraph.valve_motion: its cams and five figures
    if (in.figure_count < MG_VALVE_MOTION_BLOCK_FIGURES || !in.figures)
      throw std::invalid_argument(what + " has " + std::to_string(in.figure_count) + " figures, not the " +
                                  std::to_string(MG_VALVE_MOTION_BLOCK_FIGURES) + " of a valve motion block");
    bool one = in.object_count == 1;
    for (std::size_t f = 0; f < MG_VALVE_MOTION_BLOCK_FIGURES; ++f) {
      if (!in.figures[f].values) throw std::invalid_argument(what + ": figure " + std::to_string(f) + " has no values");
      one = one && in.figures[f].stride == 0;
    }
    const std::size_t rows = one ? 1 : cases;
    auto block = std::make_shared<ValveMotionBlock>(import_laws(in, cases, what, known), rows);
    const auto copy = [&](std::vector<double>& to, int figure) {
      const mg_block_column& c = in.figures[figure];
      for (std::size_t i = 0; i < rows; ++i) to[i] = c.values[i * c.stride];
    };
    copy(block->open_begin, MG_VALVE_MOTION_BLOCK_OPEN_BEGIN);
    copy(block->open_end, MG_VALVE_MOTION_BLOCK_OPEN_END);
    copy(block->rocker_ratio, MG_VALVE_MOTION_BLOCK_ROCKER_RATIO);
    copy(block->lash, MG_VALVE_MOTION_BLOCK_LASH);
    copy(block->camshaft_speed, MG_VALVE_MOTION_BLOCK_CAMSHAFT_SPEED);
    return block;
  }
  throw std::invalid_argument(what + ": a block of '" + std::string(kind) + "' has no C form (c/node_block.h)");
}

/// Releases an mg_object_block's owner once (an adopted output, or an input after the call).
struct MECHGRAPH_DETAIL_HIDDEN BlockOwner {
  mg_owner owner{};
  BlockOwner() = default;
  explicit BlockOwner(mg_owner o) : owner(o) {}
  BlockOwner(BlockOwner&& other) noexcept : owner(other.owner) { other.owner = {}; }
  BlockOwner& operator=(BlockOwner&&) = delete;
  ~BlockOwner() {
    if (owner.release) owner.release(owner.ctx);
  }
};

}  // namespace mechgraph::detail
