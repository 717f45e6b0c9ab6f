// mechgraph.node.cxx/1 (c/node_cxx.h): the host calls an SDK 1.x node type as itself, the plugin's
// C++ NodeType, only when the plugin's C++ layer has the host's key byte for byte and its ports carry
// only the SDK's interfaces; any other type, and every type of a registry told so (plugin-test), runs
// through its C description and evaluate function. A hand-made type answers both ways with other
// numbers, so which way the host took shows in the result; the built-in plugins are described the
// same either way and give the same rows.
#include "sweep_support.hpp"
#include "test_support.hpp"
#include "../../core/src/c_node_type.hpp"  // make_c_node_type, runs_through_c
#include <mechgraph/detail/cxx_abi_key.hpp>
#include <mechgraph/detail/export_node.hpp>
#include <mechgraph/host/node_info_format.hpp>
#include <mechgraph/json_writer.hpp>
#include <mechgraph/memo_cache.hpp>

#include <catch2/catch.hpp>

#include <sstream>
#include <string>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;

namespace {

// What reading the C description would change in a declaration.
enum class Quirk { none, private_port, required_with_default, table_with_dimension };

// y = value, declared with `quirk`.
class Constant final : public NodeType {
 public:
  explicit Constant(double value, Quirk quirk = Quirk::none) : value_(value) {
    info_.type = "test.constant";
    info_.summary = "a constant";
    info_.outputs = {PortSpec::scalar("y", Dimension{}, "the constant")};
    if (quirk == Quirk::private_port) info_.outputs.push_back(PortSpec::handle("thing", "private_thing", "an object of this plugin's own"));
    if (quirk == Quirk::required_with_default) {
      info_.params = {ParamSpec::number("gain", Dimension{}, "unused").with_default(2.0)};
      info_.params.back().required = true;
    }
    if (quirk == Quirk::table_with_dimension) {
      info_.outputs.push_back(PortSpec::table("rows", "unused"));
      info_.outputs.back().dimension = Dimension{1, 0, 0, 0, 0};
    }
  }
  const NodeInfo& info() const override { return info_; }
  void evaluate(const ParamSet&, const InputSet&, OutputSet& out, EvalContext&) const override { out.set_scalar("y", value_); }

 private:
  NodeInfo info_;
  double value_;
};

struct Quiet final : EvalContext {
  bool effect(std::string_view) const override { return false; }
  void log(LogLevel, std::string_view) override {}
  void report_work(std::string_view, double) override {}
  bool wanted(std::string_view) const override { return true; }
};

double evaluated(const NodeType& type) {
  OutputSet out;
  Quiet context;
  type.evaluate(ParamSet{}, InputSet{}, out, context);
  return out.all().at("y").as_scalar();
}

// A type whose C side (a NodeTypeExport of Constant(1)) answers mechgraph.node.cxx/1 with `table`,
// whose C++ side is Constant(2): the host's choice shows as 1 or 2.
struct TwoFaced {
  detail::NodeTypeExport exported;
  mg_node_type c_type;
  mg_node_cxx_v1 table;
  std::shared_ptr<const NodeType> cxx;

  explicit TwoFaced(Quirk quirk = Quirk::none)
      : exported(std::make_shared<const Constant>(1.0, quirk), "test"),
        c_type(*exported.c_type()),
        table{sizeof(mg_node_cxx_v1), detail::cxx_abi_key, &shared_type},
        cxx(std::make_shared<const Constant>(2.0, quirk)) {
    detail::host_suites().eval = &detail::c_eval_suite();  // what a plugin's entry fetches from its host
    original_query() = c_type.query;
    c_type.query = &query;
    current() = this;
  }
  static TwoFaced*& current() {
    static TwoFaced* p = nullptr;
    return p;
  }
  using Query = const void* (*)(const mg_node_type*, const char*, uint32_t);
  static Query& original_query() {
    static Query q = nullptr;
    return q;
  }
  static const void* query(const mg_node_type* self, const char* name, uint32_t version) {
    if (name && version == 1 && std::string(name) == MG_NODE_CXX) return &current()->table;
    return original_query()(self, name, version);
  }
  static const void* shared_type(const mg_node_type*) { return &current()->cxx; }
};

std::string described(const NodeType& type) {
  std::ostringstream text;
  JsonWriter json(text);
  host::write_node_info_json(json, type.info());
  return text.str();
}

}  // namespace

TEST_CASE("an SDK 1.x node type is called as itself only when its C++ layer is the host's", "[sdk1][cxx]") {
  if (!detail::cxx_abi_key) {
    // A host built without the shortcut (clang, libc++: detail/cxx_abi_key.hpp) has no key of its
    // own: whatever key a table claims, the type is called through C.
    TwoFaced two;
    for (const char* claimed : {"mechgraph-sdk-1.5.0/headers-0/gcc-12/libstdc++-20230528-cxx11abi1/cxxabi1017/rtti/std202002", "", "x"}) {
      CAPTURE(claimed);
      two.table.abi_key = claimed;
      const auto t = detail::make_c_node_type(two.c_type, "test", false);
      CHECK(evaluated(*t) == 1.0);
      CHECK(detail::runs_through_c(*t));
    }
    return;
  }
  TwoFaced two;
  const auto taken = [&] { return detail::make_c_node_type(two.c_type, "test", false); };
  SECTION("equal keys: the C++ type itself") {
    const auto t = taken();
    CHECK(evaluated(*t) == 2.0);
    CHECK_FALSE(detail::runs_through_c(*t));
    CHECK(t.get() == two.cxx.get());
  }
  SECTION("the registry's choice: through C") {
    const auto t = detail::make_c_node_type(two.c_type, "test", true);
    CHECK(evaluated(*t) == 1.0);
    CHECK(detail::runs_through_c(*t));
  }
  SECTION("a key one byte off, or none: through C") {
    std::string other = detail::cxx_abi_key;
    other.back() = other.back() == 'x' ? 'y' : 'x';
    two.table.abi_key = other.c_str();
    CHECK(evaluated(*taken()) == 1.0);
    two.table.abi_key = "";
    CHECK(evaluated(*taken()) == 1.0);
    two.table.abi_key = nullptr;
    CHECK(evaluated(*taken()) == 1.0);
  }
  SECTION("a short table, no function, or no type behind it: through C") {
    two.table.struct_size = offsetof(mg_node_cxx_v1, shared_type);
    CHECK(evaluated(*taken()) == 1.0);
    two.table.struct_size = sizeof(mg_node_cxx_v1);
    two.table.shared_type = nullptr;
    CHECK(evaluated(*taken()) == 1.0);
    two.table.shared_type = &TwoFaced::shared_type;
    two.cxx.reset();
    CHECK(evaluated(*taken()) == 1.0);
  }
}

TEST_CASE("a node type whose declaration C would read otherwise is read through C", "[sdk1][cxx]") {
  SECTION("a port of a plugin's private interface") {
    // Only the C description names a private interface after its plugin ("test.private_thing"),
    // which keeps two plugins' private kinds apart; the C++ type's own kind would not.
    TwoFaced two(Quirk::private_port);
    const auto t = detail::make_c_node_type(two.c_type, "test", false);
    CHECK(evaluated(*t) == 1.0);
    CHECK(detail::runs_through_c(*t));
    CHECK(t->info().outputs.at(1).handle_kind == "test.private_thing");
  }
  SECTION("a required parameter with a default") {
    TwoFaced two(Quirk::required_with_default);
    const auto t = detail::make_c_node_type(two.c_type, "test", false);
    CHECK(detail::runs_through_c(*t));
    CHECK_FALSE(t->info().params.at(0).required);
  }
  SECTION("a table port with a dimension") {
    TwoFaced two(Quirk::table_with_dimension);
    const auto t = detail::make_c_node_type(two.c_type, "test", false);
    CHECK(detail::runs_through_c(*t));
    CHECK(t->info().outputs.at(1).dimension.dimensionless());
  }
  SECTION("none of these: as itself, in a host with a key") {
    TwoFaced two(Quirk::none);
    CHECK(detail::runs_through_c(*detail::make_c_node_type(two.c_type, "test", false)) == (detail::cxx_abi_key == nullptr));
  }
}

TEST_CASE("a plugin built by another compiler is called through C, one built by the host's as itself where keyed",
          "[sdk1][cxx]") {
  // test_sdk1_other is tests/test_plugins/sdk1_cxx_plugin.cpp built by the other compiler (its key
  // names that compiler, or it has none); test_sdk1_objects_a is built by this project's compiler
  // with the shortcut at its default: on with gcc, off with clang (detail/cxx_abi_key.hpp).
  PluginRegistry registry;
  REQUIRE(std::filesystem::exists(test_plugin("test_sdk1_other")));  // clang++ and g++ are dependencies (install-deps.sh)
  registry.load_file(test_plugin("test_sdk1_other"));
  registry.load_file(test_plugin("test_sdk1_objects_a"));
  CHECK(detail::runs_through_c(*registry.find("cxx1.scale")->type));
  CHECK(detail::runs_through_c(*registry.find("cxx1.curve")->type));
  CHECK(detail::runs_through_c(*registry.find("objsa.law")->type) == (detail::cxx_abi_key == nullptr));
}

TEST_CASE("a stray work counter is refused either way, a stray output is wanted only through C", "[sdk1][cxx]") {
  // test.chaos of the arith test plugin on the pre-1.0 entry, on MECHGRAPH_PLUGIN_1 called as
  // itself, and through C.
  PluginRegistry pre, itself, through_c;
  pre.load_file(test_plugin("test_arith"));
  itself.load_file(test_plugin("test_arith_sdk1"));
  through_c.set_node_types_through_c(true);
  through_c.load_file(test_plugin("test_arith_sdk1"));
  REQUIRE(detail::runs_through_c(*itself.find("test.chaos")->type) == !shares_cxx_layer);  // itself where keyed
  REQUIRE(detail::runs_through_c(*through_c.find("test.chaos")->type));
  for (const PluginRegistry* r : {&pre, &itself, &through_c}) {
    const bool via_c = detail::runs_through_c(*r->find("test.chaos")->type);
    MemoCache cache;
    // The host answers from the outputs read (a search of a short list, asked over a hundred times
    // a stage 1-3 case); the C++ layer over C calls a name it cannot index wanted, so that the
    // node sets it and is refused for it (plugin-test, which runs through C, names the defect).
    const Graph asked = graph_from("nodes:\n  c: { type: test.chaos, params: { mode: ask_stray } }\noutputs: [ c.out ]\n", *r);
    CHECK(scalar_output(evaluate(asked, cache), "c.out") == (via_c ? 1.0 : -1.0));
    const Graph counted = graph_from("nodes:\n  c: { type: test.chaos, params: { mode: stray_counter } }\noutputs: [ c.out ]\n", *r);
    CHECK_THROWS_WITH(evaluate(counted, cache), Contains("node 'c'") && Contains("undeclared counter 'stray'"));
  }
}

TEST_CASE("the built-in plugins' node types run as themselves where keyed, described as through C, with the same rows",
          "[sdk1][cxx][plugins]") {
  const PluginRegistry& itself = project_registry();
  const PluginRegistry& through_c = project_registry_through_c();
  REQUIRE(itself.type_names() == through_c.type_names());
  std::size_t as_cxx = 0;
  for (const std::string& name : itself.type_names()) {
    INFO(name);
    const NodeType& a = *itself.find(name)->type;
    const NodeType& c = *through_c.find(name)->type;
    CHECK(detail::runs_through_c(c));
    if (!detail::runs_through_c(a)) ++as_cxx;
    // Every field the host presents, the same whichever way the type is called.
    CHECK(described(a) == described(c));
    CHECK(itself.find(name)->input_interface_versions == through_c.find(name)->input_interface_versions);
    CHECK(itself.find(name)->output_interface_versions == through_c.find(name)->output_interface_versions);
  }
  // The stage 1-3 types at least (in a build with a key: gcc's, not clang's); a type with a
  // private interface stays on C.
  for (const char* name : {"cam.kurz", "cam.polydyne", "valvetrain.valve_motion"}) {
    INFO(name);
    REQUIRE(itself.find(name));
    CHECK(detail::runs_through_c(*itself.find(name)->type) == !shares_cxx_layer);
  }
  // A type with a port of valvetrain's private interfaces keeps to C.
  REQUIRE(itself.find("valvetrain.spring_design"));
  CHECK(detail::runs_through_c(*itself.find("valvetrain.spring_design")->type));
  CHECK((as_cxx * 2 > itself.type_names().size()) == shares_cxx_layer);
  // The stage 1-3 sweep, case by case and in blocks, gives the same rows either way.
  const std::string scene = source_file_text("bench/peers/stages123_study.yaml");
  const auto cases = [] { return make_grid({parse_vary("rpm=3000rpm:8000rpm:5"), parse_vary("lash=0.1mm,0.3mm")}); };
  const Prepared p_itself = prepare(scene, cases(), itself);
  const Prepared p_c = prepare(scene, cases(), through_c);
  REQUIRE(p_itself.table.size() > 0);
  const Swept alone = sweep(p_itself, 1, 0);
  CHECK(alone.summary.failed == 0);
  CHECK(alone.rows.size() == p_itself.table.size());
  require_same_rows(alone, sweep(p_c, 1, 0));
  for (const Prepared* p : {&p_itself, &p_c}) {
    const Swept blocks = sweep(*p, 1, 4);
    CHECK(blocks.summary.in_blocks == p->table.size());
    require_same_rows(alone, blocks);
  }
}

TEST_CASE("plugin-test checks a plugin's node types through the C boundary", "[sdk1][cxx][cli]") {
  // -v logs how each plugin's types are called: `plugin-test` through C, `run` as themselves (in a
  // build with a key: gcc's, not clang's).
  std::size_t count = 0;
  for (const PluginInfo& p : project_registry().plugins())
    if (p.id == "cams") count = p.node_types.size();
  REQUIRE(count > 0);
  const std::string n = std::to_string(count);
  const std::string cams = (std::filesystem::path(MECHGRAPH_PLUGIN_DIR) / "mechgraph_cams.so").string();
  const CommandResult tested = run_cli("-v plugin-test '" + cams + "' --threads 0");
  INFO(tested.out << tested.err);
  CHECK(tested.exit_code == 0);
  CHECK_THAT(tested.err, Contains("mechgraph_cams.so (" + n + " node types, " + n + " through C, 0 called as C++)"));
  const CommandResult ran = run_cli("-v run '" + std::string(MECHGRAPH_SOURCE_DIR) + "/bench/peers/stages123_study.yaml'");
  INFO(ran.out << ran.err);
  CHECK(ran.exit_code == 0);
  CHECK_THAT(ran.err, Contains("mechgraph_cams.so (" + n + " node types, " + (shares_cxx_layer ? "0" : n) + " through C, " +
                               (shares_cxx_layer ? n : "0") + " called as C++)"));
}
