// SDK 1.1's fit, spring_model and spring interfaces (c/domain/fit.h, c/domain/spring.h) through
// mechgraph/detail/object_bridge.hpp: a C++ object exported as its C table, read back through that
// table as another library would (the object's vtable given another origin, so import_object takes
// the C path instead of unwrapping), gives the same numbers, and every reference is released once.
// The plugins' side (fits, springs and joints on MECHGRAPH_PLUGIN_1 feeding the pre-1.0 valvetrain)
// is covered by the scene tests. Beside them: a foreign table with a function missing (NULL) is
// refused at import for every SDK interface, not called.
#include <mechgraph/detail/object_bridge.hpp>
#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

#include <cstring>

#include <memory>
#include <string>

using namespace mechgraph;
using Catch::Matchers::Contains;

namespace {

// The object's own functions behind another origin, with its retains and releases counted.
struct Counts {
  int retains = 0, releases = 0;
};
Counts counts;
const mg_object_vtbl* original_vtbl = nullptr;
const char other_origin = 0;
mg_object_vtbl foreign_vtbl{};

// Makes `o` (made here) look made by another library; restore() undoes it before the last release.
void make_foreign(const mg_object* o) {
  counts = {};
  original_vtbl = o->vtbl;
  foreign_vtbl = *o->vtbl;
  foreign_vtbl.origin = &other_origin;
  // Another library of another C++ layer (c/object_cxx.h): its C tables only.
  foreign_vtbl.query = [](const mg_object* self, const char* name, uint32_t version) -> const void* {
    if (name && std::strcmp(name, MG_OBJECT_CXX) == 0) return nullptr;
    return original_vtbl->query(self, name, version);
  };
  foreign_vtbl.retain = [](const mg_object* self) {
    ++counts.retains;
    original_vtbl->retain(self);
  };
  foreign_vtbl.release = [](const mg_object* self) {
    ++counts.releases;
    original_vtbl->release(self);
  };
  const_cast<mg_object*>(o)->vtbl = &foreign_vtbl;
}

// A linear spring F = preload + rate x with one coil, and a model that makes one (or refuses a
// non-positive rate, naming its parameter as a model does).
class TestSpring final : public Spring {
 public:
  TestSpring(const SpringLine& line) : line_(line) {}
  double force(double x) const override { return line_.preload + line_.rate * x; }
  double stiffness(double) const override { return line_.rate; }
  double stroke() const override { return line_.stroke; }
  double mass() const override { return 0.045; }
  double effective_mass() const override { return 0.017; }  // not the default third: it must cross
  double surge_frequency() const override { return 612.5; }
  double stress(double x) const override { return 2.5e6 * force(x); }
  double allowable_stress() const override { return 1.1e9; }
  std::vector<CoilGeometry> coils() const override {
    return {{3.8e-3, 24.0e-3, 5.25, 7.25, 27.6e-3, 48.0e-3, line_.rate},
            {2.5e-3, 16.0e-3, 6.5, 8.5, 21.3e-3, 44.0e-3, 0.0}};
  }

 private:
  SpringLine line_;
};
class TestModel final : public SpringModel {
 public:
  std::string_view type_name() const override { return "test.spring_model"; }
  std::shared_ptr<const Spring> size(const SpringLine& line) const override {
    if (!(line.rate > 0.0)) throw NodeError("rate_limit", "the rate must be positive, got " + std::to_string(line.rate));
    return std::make_shared<const TestSpring>(line);
  }
};

}  // namespace

TEST_CASE("a fit crosses as mechgraph.fit/1 with every figure and is released once", "[sdk1][objects][fit]") {
  const auto fit = std::make_shared<const Fit>("20 H7/g6", 0.020, LimitPair{21e-6, 0.0}, LimitPair{-7e-6, -20e-6},
                                               Distribution::uniform, Distribution::triangular);
  const mg_object* c = detail::export_object(fit, "fits.iso", "");
  CHECK(fit.use_count() == 2);
  make_foreign(c);
  {
    const auto back = std::dynamic_pointer_cast<const Fit>(detail::import_object(c, MG_FIT, 1));
    REQUIRE(back);
    CHECK(back.get() != fit.get());  // read through the table: a copy, as a JointPlay is
    CHECK(back->designation() == "20 H7/g6");
    CHECK(back->nominal() == 0.020);
    CHECK(back->hole().upper == 21e-6);
    CHECK(back->hole().lower == 0.0);
    CHECK(back->shaft().upper == -7e-6);
    CHECK(back->shaft().lower == -20e-6);
    CHECK(back->hole_distribution() == Distribution::uniform);
    CHECK(back->shaft_distribution() == Distribution::triangular);
    CHECK(back->clearance_min() == fit->clearance_min());
    CHECK(back->clearance_max() == fit->clearance_max());
    const PlayTerm a = fit->clearance_term(), b = back->clearance_term();
    REQUIRE(b.links.size() == a.links.size());
    for (std::size_t i = 0; i < a.links.size(); ++i) {
      CHECK(b.links[i].label == a.links[i].label);
      CHECK(b.links[i].mean == a.links[i].mean);
      CHECK(b.links[i].half_range == a.links[i].half_range);
      CHECK(b.links[i].sensitivity == a.links[i].sensitivity);
    }
    // The copy goes out as a new object and comes home unwrapped.
    const mg_object* again = detail::export_object(back, "", "");
    CHECK(detail::import_object(again, MG_FIT, 1).get() == back.get());
    again->vtbl->release(again);
  }
  CHECK(counts.retains == 0);  // a copy holds no reference
  c->vtbl->release(c);
  CHECK(counts.releases == 1);
  CHECK(fit.use_count() == 1);
}

TEST_CASE("a fit with a distribution outside MG_DISTRIBUTION_* is refused naming it", "[sdk1][objects][fit]") {
  static const mg_fit_v1 table{sizeof(mg_fit_v1), [](const mg_object*, mg_fit_data_v1* out) {
                                 *out = {"10 bad", 0.010, {10e-6, 0.0}, {0.0, -10e-6}, MG_DISTRIBUTION_NORMAL, 7};
                               }};
  static const char origin = 0;
  static const mg_object_vtbl vtbl{sizeof(mg_object_vtbl), [](const mg_object*) {}, [](const mg_object*) {},
                                   [](const mg_object*, const char* name, uint32_t v) -> const void* {
                                     return v == 1 && std::string(name) == MG_FIT ? &table : nullptr;
                                   },
                                   [](const mg_object*) { return "c.fit"; }, &origin};
  const mg_object o{&vtbl};
  CHECK_THROWS_WITH(detail::import_object(&o, MG_FIT, 1), Contains("'10 bad' shaft") && Contains("distribution 7"));
}

TEST_CASE("an object whose SDK table lacks a function is refused at import naming the interface and its maker",
          "[sdk1][objects]") {
  // One zeroed table, long enough for any of them: struct_size says "complete", every function is NULL.
  struct Hollow {
    uint32_t struct_size;
    void* functions[16];
  };
  static Hollow table{};
  static_assert(sizeof(Hollow) >= sizeof(mg_spring_v1) && sizeof(Hollow) >= sizeof(mg_cam_law_v1));
  table.struct_size = sizeof(Hollow);
  static const char origin = 0;
  static const mg_object_vtbl vtbl{sizeof(mg_object_vtbl), [](const mg_object*) {}, [](const mg_object*) {},
                                   [](const mg_object*, const char*, uint32_t v) -> const void* { return v == 1 ? &table : nullptr; },
                                   [](const mg_object*) { return "c.hollow"; }, &origin};
  const mg_object o{&vtbl};
  for (const char* interface : {MG_SPRING, MG_SPRING_MODEL, MG_CAM_LAW, MG_FOLLOWER, MG_VALVE_MOTION}) {
    INFO(interface);
    CHECK_THROWS_WITH(detail::import_object(&o, interface, 1),
                      Contains(interface) && Contains("c.hollow") && Contains("function missing"));
  }
  for (const char* interface : {MG_FIT, MG_JOINT_PLAY}) {
    INFO(interface);
    CHECK_THROWS_WITH(detail::import_object(&o, interface, 1), Contains(interface) && Contains("without its function"));
  }
}

TEST_CASE("a spring crosses as mechgraph.spring/1 with the same numbers and is released once", "[sdk1][objects][spring]") {
  const auto spring = std::make_shared<const TestSpring>(SpringLine{250.0, 30e3, 9e-3});
  const mg_object* c = detail::export_object(spring, "springs.test", "");
  make_foreign(c);
  {
    const auto back = std::dynamic_pointer_cast<const Spring>(detail::import_object(c, MG_SPRING, 1));
    REQUIRE(back);
    CHECK(back.get() != spring.get());
    for (const double x : {0.0, 3e-3, 9e-3}) {
      CHECK(back->force(x) == spring->force(x));
      CHECK(back->stiffness(x) == spring->stiffness(x));
      CHECK(back->stress(x) == spring->stress(x));
    }
    CHECK(back->stroke() == 9e-3);
    CHECK(back->mass() == 0.045);
    CHECK(back->effective_mass() == 0.017);
    CHECK(back->surge_frequency() == 612.5);
    CHECK(back->allowable_stress() == 1.1e9);
    const std::vector<CoilGeometry> a = spring->coils(), b = back->coils();
    REQUIRE(b.size() == 2);
    for (std::size_t i = 0; i < a.size(); ++i) {
      CHECK(b[i].wire_diameter == a[i].wire_diameter);
      CHECK(b[i].mean_diameter == a[i].mean_diameter);
      CHECK(b[i].active_coils == a[i].active_coils);
      CHECK(b[i].total_coils == a[i].total_coils);
      CHECK(b[i].solid_length == a[i].solid_length);
      CHECK(b[i].free_length == a[i].free_length);
      CHECK(b[i].rate == a[i].rate);
    }
    CHECK(back->solid_deflection() == spring->solid_deflection());
    // Passed on again, the view is the original object (no wrapper of a wrapper).
    const mg_object* again = detail::export_object(back, "", "");
    CHECK(again == c);
    again->vtbl->release(again);
    CHECK(counts.retains == 2);  // the view's reference and the one passed on
  }
  CHECK(counts.releases == 2);  // both given back; the export's own one is still ours
  CHECK(spring.use_count() == 2);
  c->vtbl->release(c);
  CHECK(counts.releases == 3);
  CHECK(spring.use_count() == 1);
}

TEST_CASE("a spring model crosses as mechgraph.spring_model/1: it sizes across, and refuses naming its parameter",
          "[sdk1][objects][spring]") {
  const auto model = std::make_shared<const TestModel>();
  const mg_object* c = detail::export_object(model, "springs.test_model", "");
  make_foreign(c);
  std::weak_ptr<const Spring> sized;
  {
    const auto back = std::dynamic_pointer_cast<const SpringModel>(detail::import_object(c, MG_SPRING_MODEL, 1));
    REQUIRE(back);
    CHECK(back->type_name() == "test.spring_model");
    const SpringLine line{310.0, 42e3, 10.5e-3};
    const std::shared_ptr<const Spring> spring = back->size(line);
    REQUIRE(spring);
    sized = spring;
    CHECK(spring->force(0.0) == 310.0);
    CHECK(spring->force(line.stroke) == Approx(line.max_force()).epsilon(1e-15).margin(1e-12));
    CHECK(spring->stroke() == 10.5e-3);
    CHECK(spring->effective_mass() == 0.017);
    try {
      (void)back->size({310.0, -1.0, 10.5e-3});
      FAIL("a negative rate was sized");
    } catch (const NodeError& e) {
      CHECK(e.parameter() == "rate_limit");
      CHECK_THAT(std::string(e.what()), Contains("must be positive"));
    }
  }
  CHECK(sized.expired());  // the handed-over spring was released
  CHECK(counts.retains == 1);
  CHECK(counts.releases == 1);
  c->vtbl->release(c);
  CHECK(model.use_count() == 1);
}
