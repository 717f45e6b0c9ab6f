#include "test_support.hpp"

#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;

TEST_CASE("a good plugin loads with its descriptor and node types", "[plugins]") {
  PluginRegistry r;
  r.load_file(test_plugin("test_arith"));
  REQUIRE(r.plugins().size() == 1);
  CHECK(r.plugins()[0].id == "test_arith");
  CHECK(r.plugins()[0].version == "1.2.3");
  CHECK(r.plugins()[0].fingerprint == build_fingerprint_for_tests());
  CHECK(r.find("test.add") != nullptr);
  CHECK(r.find("test.nope") == nullptr);
  CHECK(r.type_names().size() == 11);
  CHECK(r.effect_names() == std::vector<std::string>{"test_effect", "test_extra"});
}

TEST_CASE("broken plugins are refused with a precise reason", "[plugins]") {
  SECTION("missing file") {
    PluginRegistry r;
    CHECK_THROWS_MATCHES(r.load_file("/nonexistent/mechgraph_x.so"), PluginError, Catch::Matchers::Message(
                                                                                      "plugin '/nonexistent/mechgraph_x.so': no such file"));
  }
  SECTION("not a shared library") {
    const auto file = std::filesystem::temp_directory_path() / "mechgraph_not_a_library.so";
    std::ofstream(file) << "this is text, not ELF\n";
    PluginRegistry r;
    CHECK_THROWS_WITH(r.load_file(file), Contains("not an ELF shared library"));
    std::filesystem::remove(file);
  }
  SECTION("no entry") {
    PluginRegistry r;
    CHECK_THROWS_WITH(r.load_file(test_plugin("test_no_entry")),
                      Contains("has no entry 'mechgraph_plugin'") && Contains("not a mechgraph plugin"));
  }
  SECTION("ABI mismatch names both versions") {
    PluginRegistry r;
    const std::string expected = "built for plugin ABI version " + std::to_string(plugin_abi_version_for_tests() + 1) +
                                 ", this mechgraph uses ABI version " + std::to_string(plugin_abi_version_for_tests());
    CHECK_THROWS_WITH(r.load_file(test_plugin("test_abi_mismatch")), Contains(expected));
  }
  SECTION("fingerprint mismatch") {
    PluginRegistry r;
    CHECK_THROWS_WITH(r.load_file(test_plugin("test_fingerprint")),
                      Contains("was built with 'abi1;othercc-1;cxx1'") && Contains("same toolchain"));
  }
  SECTION("duplicate node type names both plugins") {
    PluginRegistry r;
    r.load_file(test_plugin("test_arith"));
    CHECK_THROWS_WITH(r.load_file(test_plugin("test_duplicate_type")),
                      Contains("provides node type 'test.add'") && Contains("plugin 'test_arith'"));
    CHECK(r.plugins().size() == 1);  // the refused plugin left nothing behind
  }
  SECTION("the same plugin twice") {
    PluginRegistry r;
    r.load_file(test_plugin("test_arith"));
    CHECK_THROWS_WITH(r.load_file(test_plugin("test_arith")), Contains("already loaded"));
  }
  SECTION("missing folder") {
    PluginRegistry r;
    CHECK_THROWS_WITH(r.load_directory("/nonexistent/folder"), Contains("does not exist"));
  }
}

TEST_CASE("node types and the objects they make stay usable after their registry is gone", "[plugins]") {
  std::shared_ptr<const NodeType> type;
  {
    PluginRegistry r;
    r.load_file(test_plugin("test_arith"));
    type = r.find("test.constant")->type;
  }
  // The registry is gone; the node type (code in the plugin) still describes and evaluates.
  CHECK(type->info().type == "test.constant");
  ParamSet params;
  params.set("value", ParamValue::of_number(2e-3));
  OutputSet out;
  RecordingContext ctx;
  type->evaluate(params, InputSet{}, out, ctx);
  CHECK(out.all().at("out").as_scalar() == 2e-3);
  CHECK(ctx.work.at("calls") == 1.0);
}

TEST_CASE("plugin search path: --plugin-dir, then MECHGRAPH_PLUGIN_PATH, never the current folder", "[plugins]") {
  CHECK(PluginRegistry::search_path(std::filesystem::path("/x")) == std::vector<std::filesystem::path>{"/x"});
  ::setenv("MECHGRAPH_PLUGIN_PATH", "/a:/b", 1);
  CHECK(PluginRegistry::search_path(std::nullopt) == std::vector<std::filesystem::path>{"/a", "/b"});
  ::unsetenv("MECHGRAPH_PLUGIN_PATH");
  const auto fallback = PluginRegistry::search_path(std::nullopt);
  REQUIRE(fallback.size() == 1);
  CHECK(fallback[0] != ".");
  CHECK(fallback[0].is_absolute());
  // build/tests/mechgraph_tests finds build/lib/mechgraph/plugins beside its bin-like folder,
  // as an installed bin/mechgraph finds lib/mechgraph/plugins.
  CHECK(std::filesystem::equivalent(fallback[0], MECHGRAPH_PLUGIN_DIR));
}
