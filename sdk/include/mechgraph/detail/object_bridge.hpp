#pragma once
// Domain objects across the SDK 1.x C boundary (docs/design/sdk-1.0.md, sections 3.3 and 3.4),
// header-only and hidden: every shared library that includes it (a plugin, the host) has its own
// copy, so two of them never unwrap each other's C++ objects through it; only the C++ object an
// object offers under mechgraph.object.cxx/1 crosses, and only between equal keys.
//
//  - export_object: a C++ DomainObject as an mg_object (one allocation, an atomic reference count,
//    the C++ object kept alive by a shared_ptr). A CamLaw answers mechgraph.cam_law/1 and the
//    optional closed_form/1 and higher_derivatives/1 (a C++ `false`, "cannot say", is
//    MG_ERR_UNSUPPORTED); a ValveMotion answers mechgraph.valve_motion/1; a Follower answers
//    mechgraph.follower/1 (a NodeError from contact() crosses as MG_ERR_NODE naming its parameter
//    and comes back as the same NodeError); a JointPlay and a Fit (plain data) answer
//    mechgraph.joint_play/1 and mechgraph.fit/1 and are copied on import, not viewed; a SpringModel
//    answers mechgraph.spring_model/1 (its size() hands over a new mechgraph.spring/1 object, a
//    NodeError crossing as MG_ERR_NODE as for a follower) and a Spring mechgraph.spring/1. Any other kind crosses as
//    an opaque object that answers only its private interface name. An object that is itself the
//    view of a foreign mg_object is passed on as that original object (retained): no chain of
//    wrappers forms of this library's views. (Another library's C++ object taken through
//    mechgraph.object.cxx/1 is wrapped once more when passed on, naming this library's node.)
//  - import_object: the C++ view of an mg_object. One made by this very library is unwrapped to
//    its C++ object (no C hop), and so is one of an SDK interface made by a library of the same
//    C++ layer (mechgraph.object.cxx/1, c/object_cxx.h: equal keys, detail/cxx_abi_key.hpp);
//    another becomes a Foreign view (ForeignCamLaw, ForeignValveMotion,
//    ForeignFollower, ForeignSpringModel, ForeignSpring, ForeignOpaque) that holds one reference and
//    releases it when the last C++ holder lets go. A table with a required function missing (NULL)
//    is refused there, naming the interface and the maker; an incomplete optional one is absent.
// Pure maths behind the tables never throws across: an exception there is MG_ERR_INTERNAL.
#include <mechgraph/c/domain/fit.h>
#include <mechgraph/c/domain/follower.h>
#include <mechgraph/c/domain/joint_play.h>
#include <mechgraph/c/domain/spring.h>
#include <mechgraph/c/domain/valve_motion.h>
#include <mechgraph/c/object_cxx.h>
#include <mechgraph/c/sdk_lib.h>
#include <mechgraph/block.hpp>
#include <mechgraph/detail/cxx_abi_key.hpp>
#include <mechgraph/domain/cam_law.hpp>
#include <mechgraph/domain/fit.hpp>
#include <mechgraph/domain/follower.hpp>
#include <mechgraph/domain/spring.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/domain/tolerance.hpp>
#include <mechgraph/domain/valve_motion.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <typeinfo>
#include <vector>

#define MECHGRAPH_DETAIL_HIDDEN __attribute__((visibility("hidden")))

namespace mechgraph::detail {

/// The identity of this library's SDK layer (mg_object_vtbl::origin): one per shared library.
MECHGRAPH_DETAIL_HIDDEN inline const char object_origin = 0;

/// The SDK interfaces that have a C++ class: its DomainObject::kind() and its C name and version.
struct SdkInterface {
  std::string_view kind;
  const char* name;
  std::uint32_t version;
};
inline constexpr SdkInterface sdk_interfaces[] = {
    {CamLaw::kind_name, MG_CAM_LAW, 1}, {ValveMotion::kind_name, MG_VALVE_MOTION, 1}, {JointPlay::kind_name, MG_JOINT_PLAY, 1},
    {Follower::kind_name, MG_FOLLOWER, 1}, {Fit::kind_name, MG_FIT, 1}, {SpringModel::kind_name, MG_SPRING_MODEL, 1},
    {Spring::kind_name, MG_SPRING, 1}};  // SDK 1.1: fit, spring_model, spring
inline const SdkInterface* sdk_interface_of_kind(std::string_view kind) {
  for (const SdkInterface& i : sdk_interfaces)
    if (i.kind == kind) return &i;
  return nullptr;
}
inline const SdkInterface* sdk_interface_named(std::string_view name) {
  for (const SdkInterface& i : sdk_interfaces)
    if (name == i.name) return &i;
  return nullptr;
}

/// Implemented by the C++ views of objects made elsewhere: the original object, borrowed.
class MECHGRAPH_DETAIL_HIDDEN ForeignObject {
 public:
  virtual const mg_object* c_object() const = 0;

 protected:
  ~ForeignObject() = default;
};

struct ExportedBlock;

/// What every object this library exports begins with: the C++ interface its tables serve, and the
/// block it lives in (a BlockLaw) or nullptr (an Exported).
struct MECHGRAPH_DETAIL_HIDDEN ExportedHead : mg_object {
  const void* primary = nullptr;  // const CamLaw*, const ValveMotion*, const Follower*, const Spring*, const SpringModel*
  ExportedBlock* block = nullptr;
};
inline const ExportedHead& head(const mg_object* o) { return *static_cast<const ExportedHead*>(o); }

/// A C++ object as an mg_object (3.3). `mg_object` is its base, so the vtable's functions get back
/// to it with a static_cast.
struct MECHGRAPH_DETAIL_HIDDEN Exported : ExportedHead {
  mutable std::atomic<std::uint32_t> refs{1};
  std::shared_ptr<const DomainObject> self;
  std::string maker;              // the node type that made it
  std::string interface;          // an opaque object's private interface name
  const mg_object* cam = nullptr; // a valve motion's cam law, exported (one reference held)
  std::vector<mg_tolerance_link> links;  // a joint play's data, as C
  std::vector<mg_play_term> terms;
  mg_joint_play_data_v1 play{};
  mg_fit_data_v1 fit{};                  // a fit's data, as C
  ~Exported() {
    if (cam) cam->vtbl->release(cam);
  }
};
inline const Exported& exported(const mg_object* o) { return *static_cast<const Exported*>(o); }

/// A cam law of a block exported by this library (block_bridge.hpp): the block's laws live in one
/// array of it, and a reference to one of them is a reference to the block, which keeps the C++
/// block and so the law alive. No allocation and no reference count of its own per case.
struct MECHGRAPH_DETAIL_HIDDEN BlockLaw : ExportedHead {
  std::shared_ptr<const DomainObject> self;
};

/// An exported block (block_bridge.hpp): what its owner and its laws keep alive, the C++ block.
/// Destroyed when the owner has released it and no reference to one of its laws is left.
struct MECHGRAPH_DETAIL_HIDDEN ExportedBlock {
  mutable std::atomic<std::uint32_t> refs{1};  // the owner's, plus one per reference to a law in `laws`
  std::shared_ptr<const DomainBlock> keep;
  std::string maker;                           // the node type that made it
  std::vector<BlockLaw> laws;                  // the laws made here (never reallocated once filled)
  std::vector<const mg_object*> objects;       // what crosses: laws of `laws`, originals passed on, NULL
  std::vector<const mg_object*> passed_on;     // the originals, one reference each
  std::vector<mg_block_column> figures;
  ~ExportedBlock() {
    for (const mg_object* o : passed_on) o->vtbl->release(o);
  }
  static void unref(const ExportedBlock* b) {
    if (b->refs.fetch_sub(1, std::memory_order_acq_rel) == 1) delete b;
  }
  static void release(void* self) { unref(static_cast<const ExportedBlock*>(self)); }
};
inline void block_law_retain(const mg_object* o) { head(o).block->refs.fetch_add(1, std::memory_order_relaxed); }
inline void block_law_release(const mg_object* o) { ExportedBlock::unref(head(o).block); }
inline const char* block_law_maker(const mg_object* o) { return head(o).block->maker.c_str(); }

/// The C++ object behind an object this library exported.
inline const std::shared_ptr<const DomainObject>& own_self(const mg_object* o) {
  return head(o).block ? static_cast<const BlockLaw*>(o)->self : exported(o).self;
}

// --- mechgraph.object.cxx/1: the C++ object behind an exported object (SDK 1.4) -------------------
inline const void* cxx_shared_object(const mg_object* o) { return &own_self(o); }
inline const void* cxx_shared_block(const mg_object_block* b) {
  return b && b->owner.release == &ExportedBlock::release && b->owner.ctx ? &static_cast<const ExportedBlock*>(b->owner.ctx)->keep
                                                                          : nullptr;
}
MECHGRAPH_DETAIL_HIDDEN inline const mg_object_cxx_v1 object_cxx_table{sizeof(mg_object_cxx_v1), cxx_abi_key, &cxx_shared_object,
                                                                       &cxx_shared_block};
/// The answer of an object of an SDK interface to a query that its own tables did not take.
inline const void* object_cxx_query(const char* name, uint32_t version) {
#if MECHGRAPH_SDK_CXX_SHORTCUT
  return version == 1 && name && std::strcmp(name, MG_OBJECT_CXX) == 0 ? &object_cxx_table : nullptr;
#else
  (void)name, (void)version;
  return nullptr;
#endif
}
/// The table of `o` when its C++ layer is this library's (equal keys), else nullptr.
inline const mg_object_cxx_v1* same_cxx(const mg_object* o) {
#if MECHGRAPH_SDK_CXX_SHORTCUT
  const auto* t = static_cast<const mg_object_cxx_v1*>(o->vtbl->query(o, MG_OBJECT_CXX, 1));
  if (!t || t->struct_size < sizeof(mg_object_cxx_v1) || !t->abi_key || !t->shared_object || !t->shared_block) return nullptr;
  return is_own_cxx_abi_key(t->abi_key) ? t : nullptr;
#else
  (void)o;
  return nullptr;
#endif
}
/// The C++ object behind `o` when its C++ layer is this library's, else nullptr.
inline std::shared_ptr<const DomainObject> same_cxx_object(const mg_object* o) {
  const mg_object_cxx_v1* t = same_cxx(o);
  if (!t) return nullptr;
  const void* shared = t->shared_object(o);
  return shared ? *static_cast<const std::shared_ptr<const DomainObject>*>(shared) : nullptr;
}

inline void exported_retain(const mg_object* o) { exported(o).refs.fetch_add(1, std::memory_order_relaxed); }
inline void exported_release(const mg_object* o) {
  if (exported(o).refs.fetch_sub(1, std::memory_order_acq_rel) == 1) delete &exported(o);
}
inline const char* exported_maker(const mg_object* o) { return exported(o).maker.c_str(); }

// --- mechgraph.cam_law/1 and its optional tables over a C++ CamLaw ---------------------------
inline const CamLaw& law_of(const mg_object* o) { return *static_cast<const CamLaw*>(head(o).primary); }
inline constexpr double nan_result = std::numeric_limits<double>::quiet_NaN();

inline void cam_event(const mg_object* o, double* begin, double* end) {
  try {
    *begin = law_of(o).event_begin();
    *end = law_of(o).event_end();
  } catch (...) {
    *begin = *end = nan_result;
  }
}
inline mg_lift4 c_lift(const LiftDerivatives& d) { return {d.lift, d.velocity, d.acceleration, d.jerk}; }
inline mg_status cam_evaluate(const mg_object* o, double phi, mg_lift4* out) {
  try {
    *out = c_lift(law_of(o).evaluate_in_event(phi));
    return MG_OK;
  } catch (...) {
    return MG_ERR_INTERNAL;
  }
}
inline mg_status cam_evaluate_many(const mg_object* o, const double* phi, size_t n, mg_lift4* out) {
  try {
    const CamLaw& law = law_of(o);
    for (size_t i = 0; i < n; ++i) out[i] = c_lift(law.evaluate_in_event(phi[i]));
    return MG_OK;
  } catch (...) {
    return MG_ERR_INTERNAL;
  }
}
inline size_t copy_out(const std::vector<double>& v, double* out, size_t capacity) {
  if (out) std::copy_n(v.begin(), std::min(v.size(), capacity), out);
  return v.size();
}
inline size_t cam_breakpoints(const mg_object* o, double* out, size_t capacity) {
  try {
    return copy_out(law_of(o).breakpoints(), out, capacity);
  } catch (...) {
    return 0;
  }
}
template <double (CamLaw::*get)() const>
double cam_number(const mg_object* o) {
  try {
    return (law_of(o).*get)();
  } catch (...) {
    return nan_result;
  }
}
inline mg_status cam_monotone_breaks(const mg_object* o, int32_t order, double* out, size_t capacity, size_t* count) {
  try {
    // This thread's list, kept between calls (a search over a foreign law asks for every case):
    // no allocation once it has grown. Emptied first, as a new vector would be; a call made while
    // it is in use further up this thread's stack (a law wrapping a law that comes back here
    // through another library) takes a list of its own.
    thread_local std::vector<double> kept;
    thread_local bool kept_busy = false;
    std::vector<double> own;
    std::vector<double>& breaks = kept_busy ? own : kept;
    struct Busy {
      bool& flag;
      bool was;
      ~Busy() { flag = was; }
    } const busy{kept_busy, kept_busy};
    kept_busy = true;
    breaks.clear();
    if (!law_of(o).monotone_breaks(order, breaks)) return MG_ERR_UNSUPPORTED;
    *count = copy_out(breaks, out, capacity);
    return MG_OK;
  } catch (...) {
    return MG_ERR_INTERNAL;
  }
}
inline mg_status cam_lift_integrals(const mg_object* o, double a, double b, double* integral, double* of_square) {
  try {
    return law_of(o).lift_integrals(a, b, *integral, *of_square) ? MG_OK : MG_ERR_UNSUPPORTED;
  } catch (...) {
    return MG_ERR_INTERNAL;
  }
}
inline mg_status cam_d4_d5(const mg_object* o, double phi, double* d4, double* d5) {
  try {
    return law_of(o).higher_derivatives(phi, *d4, *d5) ? MG_OK : MG_ERR_UNSUPPORTED;
  } catch (...) {
    return MG_ERR_INTERNAL;
  }
}
MECHGRAPH_DETAIL_HIDDEN inline const mg_cam_law_v1 cam_law_table{sizeof(mg_cam_law_v1),
                                                                 &cam_event,
                                                                 &cam_evaluate,
                                                                 &cam_evaluate_many,
                                                                 &cam_breakpoints,
                                                                 &cam_number<&CamLaw::max_lift>,
                                                                 &cam_number<&CamLaw::base_radius>,
                                                                 &cam_number<&CamLaw::roller_radius>};
MECHGRAPH_DETAIL_HIDDEN inline const mg_cam_law_closed_form_v1 cam_closed_form_table{sizeof(mg_cam_law_closed_form_v1),
                                                                                     &cam_monotone_breaks, &cam_lift_integrals};
MECHGRAPH_DETAIL_HIDDEN inline const mg_cam_law_higher_v1 cam_higher_table{sizeof(mg_cam_law_higher_v1), &cam_d4_d5};
inline const void* cam_query(const mg_object*, const char* name, uint32_t version) {
  if (version != 1 || !name) return nullptr;
  if (std::strcmp(name, MG_CAM_LAW) == 0) return &cam_law_table;
  if (std::strcmp(name, MG_CAM_LAW_CLOSED_FORM) == 0) return &cam_closed_form_table;
  if (std::strcmp(name, MG_CAM_LAW_HIGHER) == 0) return &cam_higher_table;
  return object_cxx_query(name, version);
}
MECHGRAPH_DETAIL_HIDDEN inline const mg_object_vtbl block_law_vtbl{sizeof(mg_object_vtbl), &block_law_retain, &block_law_release,
                                                                   &cam_query, &block_law_maker, &object_origin};

// --- mechgraph.valve_motion/1 over a C++ ValveMotion -------------------------------------------
inline const ValveMotion& motion_of(const mg_object* o) { return *static_cast<const ValveMotion*>(head(o).primary); }
inline mg_status valve_at(const mg_object* o, double phi, mg_lift4* out) {
  try {
    *out = c_lift(motion_of(o).at(phi));
    return MG_OK;
  } catch (...) {
    return MG_ERR_INTERNAL;
  }
}
inline mg_status valve_at_many(const mg_object* o, const double* phi, size_t n, mg_lift4* out) {
  try {
    const ValveMotion& m = motion_of(o);
    for (size_t i = 0; i < n; ++i) out[i] = c_lift(m.at(phi[i]));
    return MG_OK;
  } catch (...) {
    return MG_ERR_INTERNAL;
  }
}
template <double (ValveMotion::*get)() const>
double valve_number(const mg_object* o) {
  try {
    return (motion_of(o).*get)();
  } catch (...) {
    return nan_result;
  }
}
inline void valve_open_period(const mg_object* o, double* begin, double* end) {
  try {
    *begin = motion_of(o).open_begin();
    *end = motion_of(o).open_end();
  } catch (...) {
    *begin = *end = nan_result;
  }
}
inline size_t valve_knots(const mg_object* o, double* out, size_t capacity) {
  try {
    return copy_out(motion_of(o).knots(), out, capacity);
  } catch (...) {
    return 0;
  }
}
inline const mg_object* valve_cam(const mg_object* o) { return exported(o).cam; }
MECHGRAPH_DETAIL_HIDDEN inline const mg_valve_motion_v1 valve_motion_table{sizeof(mg_valve_motion_v1),
                                                                           &valve_at,
                                                                           &valve_at_many,
                                                                           &valve_number<&ValveMotion::camshaft_speed>,
                                                                           &valve_open_period,
                                                                           &valve_knots,
                                                                           &valve_number<&ValveMotion::rocker_ratio>,
                                                                           &valve_number<&ValveMotion::lash>,
                                                                           &valve_cam};
inline const void* valve_query(const mg_object*, const char* name, uint32_t version) {
  return version == 1 && name && std::strcmp(name, MG_VALVE_MOTION) == 0 ? &valve_motion_table : object_cxx_query(name, version);
}

// --- mechgraph.follower/1 over a C++ Follower ------------------------------------------------
inline const Follower& follower_of(const mg_object* o) { return *static_cast<const Follower*>(head(o).primary); }
inline void send_text(const mg_text_sink& sink, std::string_view text) {
  if (sink.append) sink.append(sink.self, text.data(), text.size());
}
inline mg_text_sink string_sink(std::string* s) {
  return {s, [](void* self, const char* text, size_t size) { static_cast<std::string*>(self)->append(text, size); }};
}
inline void follower_type_name(const mg_object* o, mg_text_sink out) {
  try {
    send_text(out, follower_of(o).type_name());
  } catch (...) {
  }
}
inline void follower_describe(const mg_object* o, mg_text_sink out) {
  try {
    send_text(out, follower_of(o).describe());
  } catch (...) {
  }
}
inline double follower_roller_radius(const mg_object* o) {
  try {
    return follower_of(o).roller_radius();
  } catch (...) {
    return nan_result;
  }
}
inline int32_t follower_pivoted(const mg_object* o) {
  try {
    return follower_of(o).pivoted() ? 1 : 0;
  } catch (...) {
    return 0;
  }
}
inline double follower_cam_lever(const mg_object* o, double base_radius) {
  try {
    return follower_of(o).cam_lever(base_radius);
  } catch (...) {
    return nan_result;
  }
}
inline mg_status follower_contact(const mg_object* o, double phi, const mg_lift4* lift, double base_radius, int32_t clockwise,
                                  mg_follower_contact* out, const mg_error* err) {
  try {
    const FollowerContact c =
        follower_of(o).contact(phi, {lift->h, lift->dh, lift->d2h, lift->d3h}, base_radius, clockwise != 0);
    *out = {c.x, c.y, c.pitch_x, c.pitch_y, c.pressure_angle, c.curvature_radius, c.face_position, c.follower_angle};
    return MG_OK;
  } catch (const NodeError& e) {
    if (err && err->struct_size >= sizeof(mg_error)) {
      send_text(err->parameter, e.parameter());
      send_text(err->message, e.what());
    }
    return MG_ERR_NODE;
  } catch (...) {
    return MG_ERR_INTERNAL;
  }
}
MECHGRAPH_DETAIL_HIDDEN inline const mg_follower_v1 follower_table{sizeof(mg_follower_v1), &follower_type_name, &follower_describe,
                                                                   &follower_roller_radius, &follower_pivoted,
                                                                   &follower_cam_lever, &follower_contact};
inline const void* follower_query(const mg_object*, const char* name, uint32_t version) {
  return version == 1 && name && std::strcmp(name, MG_FOLLOWER) == 0 ? &follower_table : object_cxx_query(name, version);
}

// --- mechgraph.joint_play/1 over a C++ JointPlay: its data, built once at export ---------------
inline void joint_play_data(const mg_object* o, mg_joint_play_data_v1* out) { *out = exported(o).play; }
MECHGRAPH_DETAIL_HIDDEN inline const mg_joint_play_v1 joint_play_table{sizeof(mg_joint_play_v1), &joint_play_data};
inline const void* joint_play_query(const mg_object*, const char* name, uint32_t version) {
  return version == 1 && name && std::strcmp(name, MG_JOINT_PLAY) == 0 ? &joint_play_table : object_cxx_query(name, version);
}
inline void export_play_data(Exported& e, const JointPlay& play) {
  std::size_t count = 0;
  for (const PlayTerm& t : play.terms()) count += t.links.size();
  e.links.reserve(count);  // no reallocation: the terms point into it
  for (const PlayTerm& t : play.terms()) {
    const std::size_t first = e.links.size();
    for (const ToleranceLink& l : t.links)
      e.links.push_back({l.label.c_str(), l.mean, l.half_range, l.sensitivity, static_cast<std::int32_t>(l.distribution), 0});
    e.terms.push_back({t.label.c_str(), e.links.data() + first, t.links.size()});
  }
  e.play = {play.joint().c_str(), e.terms.data(), e.terms.size()};
}
inline std::shared_ptr<const JointPlay> import_play_data(const mg_object* o) {
  const auto* t = static_cast<const mg_joint_play_v1*>(o->vtbl->query(o, MG_JOINT_PLAY, 1));
  if (!t || t->struct_size < sizeof(mg_joint_play_v1) || !t->data)
    throw std::runtime_error("a joint_play object does not answer mechgraph.joint_play version 1 (no table, or one without its function)");
  mg_joint_play_data_v1 d{};
  t->data(o, &d);
  const auto text = [](const char* s) { return std::string(s ? s : ""); };
  std::vector<PlayTerm> terms;
  for (std::size_t i = 0; i < d.term_count; ++i) {
    PlayTerm term{text(d.terms[i].label), {}};
    for (std::size_t k = 0; k < d.terms[i].link_count; ++k) {
      const mg_tolerance_link& l = d.terms[i].links[k];
      if (l.distribution < MG_DISTRIBUTION_NORMAL || l.distribution > MG_DISTRIBUTION_TRIANGULAR)
        throw std::runtime_error("a joint_play link '" + text(l.label) + "' has distribution " + std::to_string(l.distribution) +
                                 ", not one of MG_DISTRIBUTION_*");
      term.links.push_back({text(l.label), l.mean, l.half_range, l.sensitivity, static_cast<Distribution>(l.distribution)});
    }
    terms.push_back(std::move(term));
  }
  return std::make_shared<const JointPlay>(text(d.joint), std::move(terms));
}

// --- mechgraph.fit/1 over a C++ Fit: its data, built once at export (SDK 1.1) ------------------
inline void fit_data(const mg_object* o, mg_fit_data_v1* out) { *out = exported(o).fit; }
MECHGRAPH_DETAIL_HIDDEN inline const mg_fit_v1 fit_table{sizeof(mg_fit_v1), &fit_data};
inline const void* fit_query(const mg_object*, const char* name, uint32_t version) {
  return version == 1 && name && std::strcmp(name, MG_FIT) == 0 ? &fit_table : object_cxx_query(name, version);
}
inline void export_fit_data(Exported& e, const Fit& fit) {
  e.fit = {fit.designation().c_str(), fit.nominal(), {fit.hole().upper, fit.hole().lower}, {fit.shaft().upper, fit.shaft().lower},
           static_cast<std::int32_t>(fit.hole_distribution()), static_cast<std::int32_t>(fit.shaft_distribution())};
}
inline Distribution distribution_from_c(std::int32_t d, const std::string& what) {
  if (d < MG_DISTRIBUTION_NORMAL || d > MG_DISTRIBUTION_TRIANGULAR)
    throw std::runtime_error(what + " has distribution " + std::to_string(d) + ", not one of MG_DISTRIBUTION_*");
  return static_cast<Distribution>(d);
}
inline std::shared_ptr<const Fit> import_fit_data(const mg_object* o) {
  const auto* t = static_cast<const mg_fit_v1*>(o->vtbl->query(o, MG_FIT, 1));
  if (!t || t->struct_size < sizeof(mg_fit_v1) || !t->data)
    throw std::runtime_error("a fit object does not answer mechgraph.fit version 1 (no table, or one without its function)");
  mg_fit_data_v1 d{};
  t->data(o, &d);
  std::string designation(d.designation ? d.designation : "");
  const std::string what = "the fit '" + designation + "'";
  return std::make_shared<const Fit>(std::move(designation), d.nominal, LimitPair{d.hole.upper, d.hole.lower},
                                     LimitPair{d.shaft.upper, d.shaft.lower}, distribution_from_c(d.hole_distribution, what + " hole"),
                                     distribution_from_c(d.shaft_distribution, what + " shaft"));
}

// --- mechgraph.spring/1 over a C++ Spring (SDK 1.1) ----------------------------------------------
inline const Spring& spring_of(const mg_object* o) { return *static_cast<const Spring*>(head(o).primary); }
template <double (Spring::*get)(double) const>
double spring_at(const mg_object* o, double x) {
  try {
    return (spring_of(o).*get)(x);
  } catch (...) {
    return nan_result;
  }
}
template <double (Spring::*get)() const>
double spring_number(const mg_object* o) {
  try {
    return (spring_of(o).*get)();
  } catch (...) {
    return nan_result;
  }
}
inline size_t spring_coils(const mg_object* o, mg_coil_geometry* out, size_t capacity) {
  try {
    const std::vector<CoilGeometry> coils = spring_of(o).coils();
    if (out)
      for (std::size_t i = 0; i < std::min(coils.size(), capacity); ++i) {
        const CoilGeometry& c = coils[i];
        out[i] = {c.wire_diameter, c.mean_diameter, c.active_coils, c.total_coils, c.solid_length, c.free_length, c.rate};
      }
    return coils.size();
  } catch (...) {
    return 0;
  }
}
MECHGRAPH_DETAIL_HIDDEN inline const mg_spring_v1 spring_table{sizeof(mg_spring_v1),
                                                               &spring_at<&Spring::force>,
                                                               &spring_at<&Spring::stiffness>,
                                                               &spring_number<&Spring::stroke>,
                                                               &spring_number<&Spring::mass>,
                                                               &spring_number<&Spring::effective_mass>,
                                                               &spring_number<&Spring::surge_frequency>,
                                                               &spring_at<&Spring::stress>,
                                                               &spring_number<&Spring::allowable_stress>,
                                                               &spring_coils};
inline const void* spring_query(const mg_object*, const char* name, uint32_t version) {
  return version == 1 && name && std::strcmp(name, MG_SPRING) == 0 ? &spring_table : object_cxx_query(name, version);
}

// --- mechgraph.spring_model/1 over a C++ SpringModel (SDK 1.1) -----------------------------------
inline const mg_object* export_object(const std::shared_ptr<const DomainObject>& object, std::string_view maker,
                                      std::string_view private_interface);
inline const SpringModel& spring_model_of(const mg_object* o) { return *static_cast<const SpringModel*>(head(o).primary); }
inline void spring_model_type_name(const mg_object* o, mg_text_sink out) {
  try {
    send_text(out, spring_model_of(o).type_name());
  } catch (...) {
  }
}
inline mg_status spring_model_size(const mg_object* o, const mg_spring_line* line, const mg_object** out, const mg_error* err) {
  if (!out || !line) return MG_ERR_BAD_ARGUMENT;
  *out = nullptr;
  try {
    const std::shared_ptr<const Spring> spring = spring_model_of(o).size({line->preload, line->rate, line->stroke});
    if (!spring) return MG_ERR_INTERNAL;
    *out = export_object(spring, exported(o).maker, {});
    return MG_OK;
  } catch (const NodeError& e) {
    if (err && err->struct_size >= sizeof(mg_error)) {
      send_text(err->parameter, e.parameter());
      send_text(err->message, e.what());
    }
    return MG_ERR_NODE;
  } catch (const std::bad_alloc&) {
    return MG_ERR_NO_MEMORY;
  } catch (...) {
    return MG_ERR_INTERNAL;
  }
}
MECHGRAPH_DETAIL_HIDDEN inline const mg_spring_model_v1 spring_model_table{sizeof(mg_spring_model_v1), &spring_model_type_name,
                                                                           &spring_model_size};
inline const void* spring_model_query(const mg_object*, const char* name, uint32_t version) {
  return version == 1 && name && std::strcmp(name, MG_SPRING_MODEL) == 0 ? &spring_model_table : object_cxx_query(name, version);
}

// --- an object without a C table: answers only its private interface ------------------------
MECHGRAPH_DETAIL_HIDDEN inline const std::uint32_t opaque_table = sizeof(std::uint32_t);
inline const void* opaque_query(const mg_object* o, const char* name, uint32_t version) {
  return version == 1 && name && exported(o).interface == name ? &opaque_table : nullptr;
}

MECHGRAPH_DETAIL_HIDDEN inline const mg_object_vtbl cam_law_vtbl{sizeof(mg_object_vtbl), &exported_retain, &exported_release,
                                                                 &cam_query, &exported_maker, &object_origin};
MECHGRAPH_DETAIL_HIDDEN inline const mg_object_vtbl valve_motion_vtbl{
    sizeof(mg_object_vtbl), &exported_retain, &exported_release, &valve_query, &exported_maker, &object_origin};
MECHGRAPH_DETAIL_HIDDEN inline const mg_object_vtbl follower_vtbl{sizeof(mg_object_vtbl), &exported_retain, &exported_release,
                                                                  &follower_query, &exported_maker, &object_origin};
MECHGRAPH_DETAIL_HIDDEN inline const mg_object_vtbl joint_play_vtbl{
    sizeof(mg_object_vtbl), &exported_retain, &exported_release, &joint_play_query, &exported_maker, &object_origin};
MECHGRAPH_DETAIL_HIDDEN inline const mg_object_vtbl fit_vtbl{sizeof(mg_object_vtbl), &exported_retain, &exported_release,
                                                             &fit_query, &exported_maker, &object_origin};
MECHGRAPH_DETAIL_HIDDEN inline const mg_object_vtbl spring_vtbl{sizeof(mg_object_vtbl), &exported_retain, &exported_release,
                                                                &spring_query, &exported_maker, &object_origin};
MECHGRAPH_DETAIL_HIDDEN inline const mg_object_vtbl spring_model_vtbl{
    sizeof(mg_object_vtbl), &exported_retain, &exported_release, &spring_model_query, &exported_maker, &object_origin};
MECHGRAPH_DETAIL_HIDDEN inline const mg_object_vtbl opaque_vtbl{sizeof(mg_object_vtbl), &exported_retain, &exported_release,
                                                                &opaque_query, &exported_maker, &object_origin};

inline const mg_object* export_cam_law(const std::shared_ptr<const CamLaw>& law, std::string_view maker);
inline const mg_object* export_valve_motion(const std::shared_ptr<const DomainObject>& object, const ValveMotion& motion,
                                            std::string_view maker);

/// `object` as an mg_object: a new reference, which the caller hands over or releases. `maker` is
/// the node type that made it (for messages); `private_interface` names what an object of a kind
/// without a C table answers.
inline const mg_object* export_object(const std::shared_ptr<const DomainObject>& object, std::string_view maker,
                                      std::string_view private_interface) {
  if (!object) throw std::invalid_argument("an empty domain object cannot cross the C boundary");
  // A cam law and a valve motion, the objects that cross most, without the search of the class
  // hierarchy that the cast to ForeignObject below costs when it fails (a view made here is told
  // by its type, the Foreign classes being final).
  if (object->kind() == sdk_interfaces[0].kind)
    if (const auto* law = dynamic_cast<const CamLaw*>(object.get())) return export_cam_law(std::shared_ptr<const CamLaw>(object, law), maker);
  if (object->kind() == sdk_interfaces[1].kind)
    if (const auto* motion = dynamic_cast<const ValveMotion*>(object.get())) return export_valve_motion(object, *motion, maker);
  if (const auto* foreign = dynamic_cast<const ForeignObject*>(object.get())) {  // pass the original on
    const mg_object* original = foreign->c_object();
    original->vtbl->retain(original);
    return original;
  }
  auto e = std::make_unique<Exported>();
  e->self = object;
  e->maker = maker;
  if (const auto* law = dynamic_cast<const CamLaw*>(object.get())) {
    e->vtbl = &cam_law_vtbl;
    e->primary = law;
  } else if (const auto* motion = dynamic_cast<const ValveMotion*>(object.get())) {
    return export_valve_motion(object, *motion, maker);  // a motion whose kind() is its own
  } else if (const auto* follower = dynamic_cast<const Follower*>(object.get())) {
    e->vtbl = &follower_vtbl;
    e->primary = follower;
  } else if (const auto* play = dynamic_cast<const JointPlay*>(object.get())) {
    e->vtbl = &joint_play_vtbl;
    e->primary = play;
    export_play_data(*e, *play);
  } else if (const auto* fit = dynamic_cast<const Fit*>(object.get())) {
    e->vtbl = &fit_vtbl;
    e->primary = fit;
    export_fit_data(*e, *fit);
  } else if (const auto* spring = dynamic_cast<const Spring*>(object.get())) {
    e->vtbl = &spring_vtbl;
    e->primary = spring;
  } else if (const auto* model = dynamic_cast<const SpringModel*>(object.get())) {
    e->vtbl = &spring_model_vtbl;
    e->primary = model;
  } else {
    e->vtbl = &opaque_vtbl;
    e->interface = private_interface.empty() ? std::string(object->kind()) : std::string(private_interface);
  }
  return e.release();
}

[[noreturn]] inline void throw_foreign(const mg_object* o, std::string_view interface, std::string_view what) {
  const char* maker = o->vtbl->maker ? o->vtbl->maker(o) : nullptr;
  throw std::runtime_error(std::string("the ") + std::string(interface) + " made by " + (maker && *maker ? maker : "another plugin") +
                           " " + std::string(what));
}
template <class Table>
const Table* query_table(const mg_object* o, const char* name) {
  const auto* t = static_cast<const Table*>(o->vtbl->query(o, name, 1));
  return t && t->struct_size >= sizeof(Table) ? t : nullptr;
}

/// Holds one reference to a foreign object for as long as its C++ view lives.
class MECHGRAPH_DETAIL_HIDDEN ForeignReference {
 public:
  explicit ForeignReference(const mg_object* o) : o_(o) { o_->vtbl->retain(o_); }
  ~ForeignReference() { o_->vtbl->release(o_); }
  ForeignReference(const ForeignReference&) = delete;
  ForeignReference& operator=(const ForeignReference&) = delete;
  const mg_object* get() const { return o_; }

 private:
  const mg_object* o_;
};

/// A cam law made elsewhere, seen as a C++ CamLaw (3.4). Its immutable figures are read once.
class MECHGRAPH_DETAIL_HIDDEN ForeignCamLaw final : public CamLaw, public ForeignObject {
 public:
  explicit ForeignCamLaw(const mg_object* o)
      : t_(query_table<mg_cam_law_v1>(o, MG_CAM_LAW)),
        cf_(query_table<mg_cam_law_closed_form_v1>(o, MG_CAM_LAW_CLOSED_FORM)),
        hd_(query_table<mg_cam_law_higher_v1>(o, MG_CAM_LAW_HIGHER)),
        ref_(o) {
    if (!t_) throw_foreign(o, MG_CAM_LAW, "does not answer mechgraph.cam_law version 1 (MG_ERR_MISSING_FEATURE)");
    if (!t_->event || !t_->evaluate || !t_->evaluate_many || !t_->breakpoints || !t_->max_lift || !t_->base_radius || !t_->roller_radius)
      throw_foreign(o, MG_CAM_LAW, "answers mechgraph.cam_law version 1 with a function missing from its table");
    if (cf_ && (!cf_->monotone_breaks || !cf_->lift_integrals)) cf_ = nullptr;  // optional: incomplete is absent
    if (hd_ && !hd_->d4_d5) hd_ = nullptr;
    t_->event(o, &begin_, &end_);
    max_lift_ = t_->max_lift(o);
    base_radius_ = t_->base_radius(o);
    roller_radius_ = t_->roller_radius(o);
    double buffer[32];
    const size_t n = t_->breakpoints(o, buffer, 32);
    breakpoints_.assign(buffer, buffer + std::min<size_t>(n, 32));
    if (n > 32) {
      breakpoints_.resize(n);
      breakpoints_.resize(std::min(n, t_->breakpoints(o, breakpoints_.data(), n)));
    }
  }
  const mg_object* c_object() const override { return ref_.get(); }
  double event_begin() const override { return begin_; }
  double event_end() const override { return end_; }
  LiftDerivatives evaluate_in_event(double phi) const override {
    mg_lift4 d;
    if (const mg_status s = t_->evaluate(ref_.get(), phi, &d); s != MG_OK)
      throw_foreign(ref_.get(), MG_CAM_LAW, std::string("failed to evaluate: ") + mg_status_name(s));
    return {d.h, d.dh, d.d2h, d.d3h};
  }
  std::vector<double> breakpoints() const override { return breakpoints_; }
  double max_lift() const override { return max_lift_; }
  double base_radius() const override { return base_radius_; }
  double roller_radius() const override { return roller_radius_; }
  bool higher_derivatives(double phi, double& d4, double& d5) const override {
    return hd_ && hd_->d4_d5(ref_.get(), phi, &d4, &d5) == MG_OK;
  }
  bool monotone_breaks(int order, std::vector<double>& breaks) const override {
    if (!cf_) return false;
    size_t count = 0;
    double buffer[32];
    if (cf_->monotone_breaks(ref_.get(), order, buffer, 32, &count) != MG_OK) return false;
    breaks.assign(buffer, buffer + std::min<size_t>(count, 32));
    if (count > 32) {
      breaks.resize(count);
      if (cf_->monotone_breaks(ref_.get(), order, breaks.data(), count, &count) != MG_OK) return false;
      breaks.resize(std::min(count, breaks.size()));
    }
    return true;
  }
  bool lift_integrals(double a, double b, double& integral, double& of_square) const override {
    return cf_ && cf_->lift_integrals(ref_.get(), a, b, &integral, &of_square) == MG_OK;
  }

 private:
  const mg_cam_law_v1* t_;
  const mg_cam_law_closed_form_v1* cf_;
  const mg_cam_law_higher_v1* hd_;
  ForeignReference ref_;
  double begin_ = 0, end_ = 0, max_lift_ = 0, base_radius_ = 0, roller_radius_ = 0;
  std::vector<double> breakpoints_;
};

/// A follower made elsewhere, seen as a C++ Follower. Its names and fixed dimensions are read once;
/// an infeasible contact (MG_ERR_NODE) comes back as the NodeError naming the follower's parameter.
class MECHGRAPH_DETAIL_HIDDEN ForeignFollower final : public Follower, public ForeignObject {
 public:
  explicit ForeignFollower(const mg_object* o) : t_(query_table<mg_follower_v1>(o, MG_FOLLOWER)), ref_(o) {
    if (!t_) throw_foreign(o, MG_FOLLOWER, "does not answer mechgraph.follower version 1 (MG_ERR_MISSING_FEATURE)");
    if (!t_->type_name || !t_->describe || !t_->roller_radius || !t_->pivoted || !t_->cam_lever || !t_->contact)
      throw_foreign(o, MG_FOLLOWER, "answers mechgraph.follower version 1 with a function missing from its table");
    t_->type_name(o, string_sink(&type_name_));
    t_->describe(o, string_sink(&describe_));
    roller_radius_ = t_->roller_radius(o);
    pivoted_ = t_->pivoted(o) != 0;
  }
  const mg_object* c_object() const override { return ref_.get(); }
  std::string_view type_name() const override { return type_name_; }
  std::string describe() const override { return describe_; }
  double roller_radius() const override { return roller_radius_; }
  bool pivoted() const override { return pivoted_; }
  double cam_lever(double base_radius) const override { return t_->cam_lever(ref_.get(), base_radius); }
  FollowerContact contact(double phi, const LiftDerivatives& d, double base_radius, bool clockwise) const override {
    const mg_lift4 lift = c_lift(d);
    mg_follower_contact c{};
    std::string parameter, message;
    const mg_error err{sizeof(mg_error), string_sink(&parameter), string_sink(&message)};
    const mg_status s = t_->contact(ref_.get(), phi, &lift, base_radius, clockwise ? 1 : 0, &c, &err);
    if (s == MG_ERR_NODE)
      throw NodeError(parameter, message.empty() ? "the " + named() + " cannot sit on this base circle" : message);
    if (s != MG_OK) throw_foreign(ref_.get(), MG_FOLLOWER, std::string("failed at a contact: ") + mg_status_name(s));
    FollowerContact out;
    out.x = c.x;
    out.y = c.y;
    out.pitch_x = c.pitch_x;
    out.pitch_y = c.pitch_y;
    out.pressure_angle = c.pressure_angle;
    out.curvature_radius = c.curvature_radius;
    out.face_position = c.face_position;
    out.follower_angle = c.follower_angle;
    return out;
  }

 private:
  const mg_follower_v1* t_;
  ForeignReference ref_;
  std::string type_name_, describe_;
  double roller_radius_ = 0;
  bool pivoted_ = false;
};

/// An object of an interface this library has no C++ class for (a plugin's private one).
class MECHGRAPH_DETAIL_HIDDEN ForeignOpaque final : public DomainObject, public ForeignObject {
 public:
  ForeignOpaque(const mg_object* o, std::string interface, std::uint32_t version)
      : ref_(o), interface_(std::move(interface)), version_(version) {}
  const mg_object* c_object() const override { return ref_.get(); }
  std::string_view kind() const override { return interface_; }
  // The SDK library's checks for SDK interfaces (mg_check_object), none for a plugin's own.
  std::string contract_problem() const override {
    std::string problem;
    const mg_text_sink sink{&problem, [](void* self, const char* text, size_t size) { static_cast<std::string*>(self)->append(text, size); }};
    const mg_status s = mg_check_object(ref_.get(), interface_.c_str(), version_, sink);
    if (s == MG_OK) return {};
    return problem.empty() ? std::string("mg_check_object says ") + mg_status_name(s) : problem;
  }

 private:
  ForeignReference ref_;
  std::string interface_;
  std::uint32_t version_;
};

std::shared_ptr<const DomainObject> import_object(const mg_object* o, std::string_view interface, std::uint32_t version);
std::shared_ptr<const CamLaw> import_cam_law(const mg_object* o);

/// A valve motion made elsewhere, seen as a C++ ValveMotion; its cam law imported beside it.
class MECHGRAPH_DETAIL_HIDDEN ForeignValveMotion final : public ValveMotion, public ForeignObject {
 public:
  explicit ForeignValveMotion(const mg_object* o) : t_(query_table<mg_valve_motion_v1>(o, MG_VALVE_MOTION)), ref_(o) {
    if (!t_) throw_foreign(o, MG_VALVE_MOTION, "does not answer mechgraph.valve_motion version 1 (MG_ERR_MISSING_FEATURE)");
    if (!t_->at || !t_->at_many || !t_->camshaft_speed || !t_->open_period || !t_->knots || !t_->rocker_ratio || !t_->lash || !t_->cam)
      throw_foreign(o, MG_VALVE_MOTION, "answers mechgraph.valve_motion version 1 with a function missing from its table");
    const mg_object* cam = t_->cam(o);
    if (!cam) throw_foreign(o, MG_VALVE_MOTION, "gives no cam law");
    cam_ = import_cam_law(cam);
    if (!cam_) throw_foreign(o, MG_VALVE_MOTION, "gives a cam law that is not one");
    t_->open_period(o, &begin_, &end_);
    speed_ = t_->camshaft_speed(o);
    ratio_ = t_->rocker_ratio(o);
    lash_ = t_->lash(o);
    knots_.resize(t_->knots(o, nullptr, 0));
    knots_.resize(std::min(knots_.size(), t_->knots(o, knots_.data(), knots_.size())));
  }
  const mg_object* c_object() const override { return ref_.get(); }
  LiftDerivatives at(double phi) const override {
    mg_lift4 d;
    if (const mg_status s = t_->at(ref_.get(), phi, &d); s != MG_OK)
      throw_foreign(ref_.get(), MG_VALVE_MOTION, std::string("failed to evaluate: ") + mg_status_name(s));
    return {d.h, d.dh, d.d2h, d.d3h};
  }
  double camshaft_speed() const override { return speed_; }
  double open_begin() const override { return begin_; }
  double open_end() const override { return end_; }
  const std::vector<double>& knots() const override { return knots_; }
  double rocker_ratio() const override { return ratio_; }
  double lash() const override { return lash_; }
  const CamLaw& cam() const override { return *cam_; }

 private:
  const mg_valve_motion_v1* t_;
  ForeignReference ref_;
  std::shared_ptr<const CamLaw> cam_;
  double begin_ = 0, end_ = 0, speed_ = 0, ratio_ = 0, lash_ = 0;
  std::vector<double> knots_;
};

/// A spring made elsewhere, seen as a C++ Spring. Its fixed figures and coils are read once.
class MECHGRAPH_DETAIL_HIDDEN ForeignSpring final : public Spring, public ForeignObject {
 public:
  explicit ForeignSpring(const mg_object* o) : t_(query_table<mg_spring_v1>(o, MG_SPRING)), ref_(o) {
    if (!t_) throw_foreign(o, MG_SPRING, "does not answer mechgraph.spring version 1 (MG_ERR_MISSING_FEATURE)");
    if (!t_->force || !t_->stiffness || !t_->stroke || !t_->mass || !t_->effective_mass || !t_->surge_frequency || !t_->stress ||
        !t_->allowable_stress || !t_->coils)
      throw_foreign(o, MG_SPRING, "answers mechgraph.spring version 1 with a function missing from its table");
    stroke_ = t_->stroke(o);
    mass_ = t_->mass(o);
    effective_mass_ = t_->effective_mass(o);
    surge_ = t_->surge_frequency(o);
    allowable_ = t_->allowable_stress(o);
    std::vector<mg_coil_geometry> c(t_->coils(o, nullptr, 0));
    c.resize(std::min(c.size(), t_->coils(o, c.data(), c.size())));
    for (const mg_coil_geometry& g : c)
      coils_.push_back({g.wire_diameter, g.mean_diameter, g.active_coils, g.total_coils, g.solid_length, g.free_length, g.rate});
  }
  const mg_object* c_object() const override { return ref_.get(); }
  double force(double x) const override { return t_->force(ref_.get(), x); }
  double stiffness(double x) const override { return t_->stiffness(ref_.get(), x); }
  double stress(double x) const override { return t_->stress(ref_.get(), x); }
  double stroke() const override { return stroke_; }
  double mass() const override { return mass_; }
  double effective_mass() const override { return effective_mass_; }
  double surge_frequency() const override { return surge_; }
  double allowable_stress() const override { return allowable_; }
  std::vector<CoilGeometry> coils() const override { return coils_; }

 private:
  const mg_spring_v1* t_;
  ForeignReference ref_;
  double stroke_ = 0, mass_ = 0, effective_mass_ = 0, surge_ = 0, allowable_ = 0;
  std::vector<CoilGeometry> coils_;
};

/// A spring model made elsewhere, seen as a C++ SpringModel: size() hands back the sized spring
/// as a C++ Spring, and a model's refusal (MG_ERR_NODE) as the NodeError naming its parameter.
class MECHGRAPH_DETAIL_HIDDEN ForeignSpringModel final : public SpringModel, public ForeignObject {
 public:
  explicit ForeignSpringModel(const mg_object* o) : t_(query_table<mg_spring_model_v1>(o, MG_SPRING_MODEL)), ref_(o) {
    if (!t_) throw_foreign(o, MG_SPRING_MODEL, "does not answer mechgraph.spring_model version 1 (MG_ERR_MISSING_FEATURE)");
    if (!t_->type_name || !t_->size)
      throw_foreign(o, MG_SPRING_MODEL, "answers mechgraph.spring_model version 1 with a function missing from its table");
    t_->type_name(o, string_sink(&type_name_));
  }
  const mg_object* c_object() const override { return ref_.get(); }
  std::string_view type_name() const override { return type_name_; }
  std::shared_ptr<const Spring> size(const SpringLine& line) const override {
    const mg_spring_line c{line.preload, line.rate, line.stroke};
    const mg_object* made = nullptr;
    std::string parameter, message;
    const mg_error err{sizeof(mg_error), string_sink(&parameter), string_sink(&message)};
    const mg_status s = t_->size(ref_.get(), &c, &made, &err);
    if (s == MG_ERR_NODE) {
      if (made) made->vtbl->release(made);
      throw NodeError(parameter, message.empty() ? type_name_ + " cannot give this spring line" : message);
    }
    if (s != MG_OK || !made) {
      if (made) made->vtbl->release(made);
      throw_foreign(ref_.get(), MG_SPRING_MODEL, std::string("failed to size a spring: ") + mg_status_name(s));
    }
    struct HandedOver {  // the new reference size() gave us: released once, whatever follows
      const mg_object* o;
      ~HandedOver() { o->vtbl->release(o); }
    } const handed_over{made};
    auto spring = std::dynamic_pointer_cast<const Spring>(import_object(made, MG_SPRING, 1));
    if (!spring) throw_foreign(ref_.get(), MG_SPRING_MODEL, "gave a spring that is not one");
    return spring;
  }

 private:
  const mg_spring_model_v1* t_;
  ForeignReference ref_;
  std::string type_name_;
};

/// A cam law as an mg_object (a new reference), as export_object makes it, for the blocks of
/// laws that cross once per case (block_bridge.hpp): the law's class is known, so no cast searches
/// the class hierarchy (a view of a foreign law, ForeignCamLaw being final, is told by its type).
inline const mg_object* export_cam_law(const std::shared_ptr<const CamLaw>& law, std::string_view maker) {
  if (!law) throw std::invalid_argument("an empty domain object cannot cross the C boundary");
  // The address of the type's typeinfo, not its name: a ForeignCamLaw of another library (another
  // SDK's layout) must not be taken for this one's; such a law takes the general wrapper below.
  const CamLaw& object = *law;
  if (&typeid(object) == &typeid(ForeignCamLaw)) {  // pass the original on
    const mg_object* original = static_cast<const ForeignCamLaw&>(object).c_object();
    original->vtbl->retain(original);
    return original;
  }
  auto e = std::make_unique<Exported>();
  e->self = law;
  e->maker = maker;
  e->vtbl = &cam_law_vtbl;
  e->primary = law.get();
  return e.release();
}

/// A valve motion as an mg_object (a new reference), as export_object makes it, without its search
/// of the class hierarchy: a view of a foreign motion (ForeignValveMotion being final) passes the
/// original on.
inline const mg_object* export_valve_motion(const std::shared_ptr<const DomainObject>& object, const ValveMotion& motion,
                                            std::string_view maker) {
  if (&typeid(motion) == &typeid(ForeignValveMotion)) {
    const mg_object* original = static_cast<const ForeignValveMotion&>(motion).c_object();
    original->vtbl->retain(original);
    return original;
  }
  auto e = std::make_unique<Exported>();
  e->self = object;
  e->maker = maker;
  e->vtbl = &valve_motion_vtbl;
  e->primary = &motion;
  // Its cam law, exported once: keeps the motion alive (aliasing) as long as someone holds the law.
  e->cam = export_cam_law(std::shared_ptr<const CamLaw>(object, &motion.cam()), maker);
  return e.release();
}

/// The C++ view of `o` (borrowed) as a cam law, as import_object(o, MG_CAM_LAW, 1) gives it but
/// typed: this library's own law unwrapped, another's a ForeignCamLaw.
inline std::shared_ptr<const CamLaw> import_cam_law(const mg_object* o) {
  if (!o || !o->vtbl) throw std::invalid_argument("an input object is missing or has no vtable");
  if (o->vtbl->origin == &object_origin) {  // made here: no C hop
    if (o->vtbl == &cam_law_vtbl || o->vtbl == &block_law_vtbl)
      return std::shared_ptr<const CamLaw>(own_self(o), static_cast<const CamLaw*>(head(o).primary));
    return std::dynamic_pointer_cast<const CamLaw>(own_self(o));
  }
  // One C++ layer: no C hop, when the object answers mechgraph.cam_law through C as well (what
  // another consumer would see), as import_object asks.
  if (auto same = same_cxx_object(o); same && o->vtbl->query(o, MG_CAM_LAW, 1))
    if (auto law = std::dynamic_pointer_cast<const CamLaw>(std::move(same))) return law;
  return std::make_shared<const ForeignCamLaw>(o);
}

/// Whether `object` implements the SDK interface at `position` in sdk_interfaces.
inline bool implements_sdk_interface(const DomainObject& object, std::ptrdiff_t position) {
  switch (position) {
    case 0: return dynamic_cast<const CamLaw*>(&object) != nullptr;
    case 1: return dynamic_cast<const ValveMotion*>(&object) != nullptr;
    case 2: return dynamic_cast<const JointPlay*>(&object) != nullptr;
    case 3: return dynamic_cast<const Follower*>(&object) != nullptr;
    case 4: return dynamic_cast<const Fit*>(&object) != nullptr;
    case 5: return dynamic_cast<const SpringModel*>(&object) != nullptr;
    case 6: return dynamic_cast<const Spring*>(&object) != nullptr;
    default: return false;
  }
}

/// The C++ view of `o` (borrowed) as a port declaring `interface`/`version` sees it. Throws
/// std::runtime_error naming the interface when the object does not answer it.
inline std::shared_ptr<const DomainObject> import_object(const mg_object* o, std::string_view interface, std::uint32_t version) {
  if (!o || !o->vtbl) throw std::invalid_argument("an input object is missing or has no vtable");
  if (o->vtbl->origin == &object_origin) return own_self(o);  // made here: no C hop
  // (By position in sdk_interfaces, not by kind_name: reading those static members here would
  // make the plugin export them.)
  if (const SdkInterface* known = sdk_interface_named(interface)) {
    // One C++ layer: the object itself, no C hop, when it offers the interface through C as well
    // (what another consumer would see) and its class is the interface's (its kind() names it, or a
    // cast finds it beside another).
    if (auto same = same_cxx_object(o);
        same && o->vtbl->query(o, known->name, version) &&
        (same->kind() == known->kind || implements_sdk_interface(*same, known - sdk_interfaces)))
      return same;
    switch (known - sdk_interfaces) {
      case 0: return std::make_shared<const ForeignCamLaw>(o);
      case 1: return std::make_shared<const ForeignValveMotion>(o);
      case 2: return import_play_data(o);
      case 3: return std::make_shared<const ForeignFollower>(o);
      case 4: return import_fit_data(o);
      case 5: return std::make_shared<const ForeignSpringModel>(o);
      case 6: return std::make_shared<const ForeignSpring>(o);
      default: break;
    }
  }
  return std::make_shared<const ForeignOpaque>(o, std::string(interface), version);
}

}  // namespace mechgraph::detail
