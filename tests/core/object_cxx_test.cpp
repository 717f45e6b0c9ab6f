// mechgraph.object.cxx/1 (c/object_cxx.h): a consumer uses the C++ object behind a domain object
// only when the producer's C++ layer has this library's key, byte for byte; otherwise it keeps to
// the object's C tables. A hand-made object here answers both: its C tables give one law, its C++
// side another, so which one the import took shows in the numbers.
#include <mechgraph/detail/block_bridge.hpp>
#include <mechgraph/detail/object_bridge.hpp>
#include <mechgraph/domain/valve_motion.hpp>

#include <catch2/catch.hpp>

#include <cstring>
#include <memory>
#include <string>

using namespace mechgraph;

namespace {

// h = H (1 - phi^2) on (-1, 1): the law behind the C tables.
constexpr double c_lift = 0.004;
// h = H (1 - phi^2) with another H: the C++ law behind mechgraph.object.cxx.
constexpr double cxx_lift = 0.009;

class Parabola final : public CamLaw {
 public:
  explicit Parabola(double lift) : lift_(lift) {}
  double event_begin() const override { return -1.0; }
  double event_end() const override { return 1.0; }
  LiftDerivatives evaluate_in_event(double phi) const override { return {lift_ * (1.0 - phi * phi), -2.0 * lift_ * phi, -2.0 * lift_, 0.0}; }
  std::vector<double> breakpoints() const override { return {}; }
  double max_lift() const override { return lift_; }
  double base_radius() const override { return 0.02; }

 private:
  double lift_;
};

// An object of "another library": its own origin, C functions that compute c_lift's parabola, and a
// mechgraph.object.cxx table with the key `key`.
struct HandMade {
  mg_object base;
  std::string key;
  std::shared_ptr<const DomainObject> cxx;
  mg_object_cxx_v1 cxx_table;
  int retained = 0;
};
const HandMade& hand_made(const mg_object* o) { return *reinterpret_cast<const HandMade*>(o); }

const char other_origin = 0;
void event(const mg_object*, double* b, double* e) { *b = -1.0, *e = 1.0; }
mg_status evaluate(const mg_object*, double phi, mg_lift4* out) {
  *out = {c_lift * (1.0 - phi * phi), -2.0 * c_lift * phi, -2.0 * c_lift, 0.0};
  return MG_OK;
}
mg_status evaluate_many(const mg_object* o, const double* phi, size_t n, mg_lift4* out) {
  for (size_t i = 0; i < n; ++i) evaluate(o, phi[i], out + i);
  return MG_OK;
}
size_t breakpoints(const mg_object*, double*, size_t) { return 0; }
double max_lift(const mg_object*) { return c_lift; }
double base_radius(const mg_object*) { return 0.02; }
double roller_radius(const mg_object*) { return 0.0; }
const mg_cam_law_v1 law_table{sizeof(mg_cam_law_v1), &event, &evaluate, &evaluate_many, &breakpoints, &max_lift, &base_radius, &roller_radius};

const void* query(const mg_object* o, const char* name, uint32_t version) {
  if (version != 1) return nullptr;
  if (std::strcmp(name, MG_CAM_LAW) == 0) return &law_table;
  if (std::strcmp(name, MG_OBJECT_CXX) == 0) return &hand_made(o).cxx_table;
  return nullptr;
}
void retain(const mg_object* o) { ++const_cast<HandMade&>(hand_made(o)).retained; }
void release(const mg_object* o) { --const_cast<HandMade&>(hand_made(o)).retained; }
const char* maker(const mg_object*) { return "test.hand_made"; }
const mg_object_vtbl vtbl{sizeof(mg_object_vtbl), &retain, &release, &query, &maker, &other_origin};

// The same object's C tables answering no cam law: only mechgraph.object.cxx.
const void* query_cxx_only(const mg_object* o, const char* name, uint32_t version) {
  return version == 1 && std::strcmp(name, MG_OBJECT_CXX) == 0 ? &hand_made(o).cxx_table : nullptr;
}
const mg_object_vtbl cxx_only_vtbl{sizeof(mg_object_vtbl), &retain, &release, &query_cxx_only, &maker, &other_origin};

const void* shared_object(const mg_object* o) { return &hand_made(o).cxx; }
const void* no_block(const mg_object_block*) { return nullptr; }

// This library's key, or for a build without one (clang, libc++: detail/cxx_abi_key.hpp) the key a
// gcc-built library of this SDK would claim: no key is then this library's own.
std::string own_or_claimed_key() {
  return detail::cxx_abi_key ? detail::cxx_abi_key
                             : "mechgraph-sdk-1.5.0/headers-0/gcc-12/libstdc++-20230528-cxx11abi1/cxxabi1017/rtti/std202002";
}

std::unique_ptr<HandMade> make(std::string key) {
  auto h = std::make_unique<HandMade>();
  h->base.vtbl = &vtbl;
  h->key = std::move(key);
  h->cxx = std::make_shared<const Parabola>(cxx_lift);
  h->cxx_table = {sizeof(mg_object_cxx_v1), h->key.c_str(), &shared_object, &no_block};
  return h;
}

}  // namespace

TEST_CASE("object cxx: an object whose C++ layer has this library's key is used as its C++ object", "[sdk1][objects][cxx]") {
  if (!detail::cxx_abi_key) {
    // No key of its own: the object is read through its C tables whatever it claims.
    const auto h = make(own_or_claimed_key());
    {
      const std::shared_ptr<const CamLaw> law = detail::import_cam_law(&h->base);
      CHECK(dynamic_cast<const detail::ForeignObject*>(law.get()) != nullptr);
      CHECK_THAT(law->at(0.0).lift, Catch::Matchers::WithinRel(c_lift, 1e-15));
      CHECK(h->retained == 1);
    }
    CHECK(h->retained == 0);
    return;
  }
  const auto h = make(detail::cxx_abi_key);
  const std::shared_ptr<const CamLaw> law = detail::import_cam_law(&h->base);
  CHECK(law.get() == h->cxx.get());  // the very object, no view
  CHECK_THAT(law->at(0.0).lift, Catch::Matchers::WithinRel(cxx_lift, 1e-15));
  CHECK(h->retained == 0);  // a shared_ptr of its own, no C reference taken
  CHECK(detail::import_object(&h->base, MG_CAM_LAW, 1).get() == h->cxx.get());
  // A port of another SDK interface than the object's C++ class implements is not handed it.
  CHECK_THROWS(detail::import_object(&h->base, MG_FOLLOWER, 1));
}

TEST_CASE("object cxx: a C++ cam law whose C tables answer no cam law is not taken as one", "[sdk1][objects][cxx]") {
  const auto h = make(own_or_claimed_key());
  h->base.vtbl = &cxx_only_vtbl;
  // Another consumer would find no cam law here: neither does this one, by either import.
  CHECK_THROWS(detail::import_cam_law(&h->base));
  CHECK_THROWS(detail::import_object(&h->base, MG_CAM_LAW, 1));
  CHECK(h->retained == 0);
}

namespace {
// A valve motion of someone's own kind (kind() is not "valve_motion"): exported by the search of
// the class hierarchy, it crosses as a valve motion with its cam law all the same.
class OwnKindMotion final : public ValveMotion {
 public:
  std::string_view kind() const override { return "test.own_motion"; }
  LiftDerivatives at(double phi) const override { return drive(phi); }
  double camshaft_speed() const override { return 300.0; }
  double open_begin() const override { return -1.0; }
  double open_end() const override { return 1.0; }
  const std::vector<double>& knots() const override { return knots_; }
  double rocker_ratio() const override { return 1.5; }
  double lash() const override { return 0.0; }
  const CamLaw& cam() const override { return law_; }

 private:
  Parabola law_{c_lift};
  std::vector<double> knots_{-1.0, 1.0};
};
}  // namespace

TEST_CASE("object cxx: a valve motion of its own kind crosses as a valve motion with its cam law", "[sdk1][objects][cxx]") {
  const auto motion = std::make_shared<const OwnKindMotion>();
  const mg_object* o = detail::export_object(motion, "test.motion", {});
  REQUIRE(o);
  const auto* table = static_cast<const mg_valve_motion_v1*>(o->vtbl->query(o, MG_VALVE_MOTION, 1));
  REQUIRE(table);
  const mg_object* cam = table->cam(o);
  REQUIRE(cam);
  const auto* law = static_cast<const mg_cam_law_v1*>(cam->vtbl->query(cam, MG_CAM_LAW, 1));
  REQUIRE(law);
  mg_lift4 at_zero{};
  REQUIRE(law->evaluate(cam, 0.0, &at_zero) == MG_OK);
  CHECK_THAT(at_zero.h, Catch::Matchers::WithinRel(c_lift, 1e-15));
  CHECK_THAT(table->rocker_ratio(o), Catch::Matchers::WithinRel(1.5, 1e-15));
  o->vtbl->release(o);
}

TEST_CASE("object cxx: a key that differs in one byte, or none, keeps the import to the C tables", "[sdk1][objects][cxx]") {
  std::string other = own_or_claimed_key();
  other.back() = other.back() == 'x' ? 'y' : 'x';
  for (const std::string& key : {other, std::string(), own_or_claimed_key().substr(1)}) {
    CAPTURE(key);
    const auto h = make(key);
    {
      const std::shared_ptr<const CamLaw> law = detail::import_cam_law(&h->base);
      CHECK(law.get() != h->cxx.get());
      CHECK(dynamic_cast<const detail::ForeignObject*>(law.get()) != nullptr);
      CHECK_THAT(law->at(0.0).lift, Catch::Matchers::WithinRel(c_lift, 1e-15));
      CHECK(h->retained == 1);  // the view holds one reference
      CHECK(dynamic_cast<const detail::ForeignObject*>(detail::import_object(&h->base, MG_CAM_LAW, 1).get()) != nullptr);
    }
    CHECK(h->retained == 0);
  }
}

TEST_CASE("object cxx: a block comes over as its C++ block only from the library that made it", "[sdk1][objects][cxx]") {
  // A block this library exports, seen by a consumer of the same key: the very C++ block (none in
  // a build without a key).
  auto laws = std::make_shared<const CamLawBlock>(std::vector<std::shared_ptr<const CamLaw>>{std::make_shared<const Parabola>(0.003),
                                                                                             std::make_shared<const Parabola>(0.005)});
  const mg_object_block exported = detail::export_block(laws, "test.block");
  const detail::BlockOwner owner(exported.owner);
  CHECK(detail::same_cxx_block(exported).get() == (detail::cxx_abi_key ? laws.get() : nullptr));
  // The same objects in a block owned by someone else: no C++ block to take; each law is then its
  // C++ object all the same (equal keys).
  mg_object_block copied = exported;
  copied.owner = {nullptr, nullptr};
  copied.origin = &other_origin;
  CHECK(detail::same_cxx_block(copied) == nullptr);
}
