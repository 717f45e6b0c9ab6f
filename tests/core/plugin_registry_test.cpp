#include "test_support.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/version.hpp>

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
                      Contains("has no entry 'mechgraph_plugin_entry'") && Contains("not a mechgraph plugin"));
  }
  SECTION("the entry of ABI 3 and older: says it was built for an older mechgraph") {
    PluginRegistry r;
    CHECK_THROWS_WITH(r.load_file(test_plugin("test_legacy_entry")),
                      Contains("built for mechgraph plugin ABI 3 or older") && Contains("rebuild the plugin against") &&
                          Contains("find_package(mechgraph"));
  }
  SECTION("ABI mismatch names both versions") {
    PluginRegistry r;
    const std::string expected = "built for plugin ABI version " + std::to_string(plugin_abi_version_for_tests() + 1) +
                                 ", this mechgraph " MECHGRAPH_SDK_VERSION " uses ABI version " + std::to_string(plugin_abi_version_for_tests());
    CHECK_THROWS_WITH(r.load_file(test_plugin("test_abi_mismatch")), Contains(expected));
  }
  SECTION("built with another C++ standard: names the standard and what to rebuild with") {
    PluginRegistry r;
    CHECK_THROWS_WITH(r.load_file(test_plugin("test_fingerprint")),
                      Contains("('foreign')") && Contains("C++ standard: plugin C++23") &&
                          Contains("mechgraph C++20") && Contains("rebuild the plugin with -std=c++20"));
  }
  SECTION("a version that is not MAJOR.MINOR.PATCH") {
    PluginRegistry r;
    CHECK_THROWS_WITH(r.load_file(test_plugin("test_bad_version")),
                      Contains("('sloppy')") && Contains("'v2-beta' is not a semantic version MAJOR.MINOR.PATCH"));
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

TEST_CASE("plugin search path: --plugin-dir adds to MECHGRAPH_PLUGIN_PATH and the built-ins, --only-plugin-dir replaces", "[plugins]") {
  const auto builtin = PluginRegistry::builtin_plugin_dir();
  REQUIRE(builtin.is_absolute());
  // Found relative to libmechgraph (build/lib/libmechgraph.so -> build/lib/mechgraph/plugins), as an
  // installed lib/libmechgraph.so finds lib/mechgraph/plugins: no build path is baked in.
  CHECK(std::filesystem::equivalent(builtin, MECHGRAPH_PLUGIN_DIR));
  ::unsetenv("MECHGRAPH_PLUGIN_PATH");
  using Paths = std::vector<std::filesystem::path>;
  CHECK(PluginRegistry::search_path({"/x"}, false) == Paths{"/x", builtin});
  CHECK(PluginRegistry::search_path({"/x", "/y"}, true) == Paths{"/x", "/y"});
  ::setenv("MECHGRAPH_PLUGIN_PATH", "/a:/b", 1);
  CHECK(PluginRegistry::search_path({"/x"}, false) == Paths{"/x", "/a", "/b", builtin});
  CHECK(PluginRegistry::search_path({}, true).empty());
  ::unsetenv("MECHGRAPH_PLUGIN_PATH");
  // A folder named twice is searched once; "." is never added.
  const auto twice = PluginRegistry::search_path({builtin}, false);
  CHECK(twice == Paths{builtin});
  for (const auto& p : PluginRegistry::search_path({}, false)) CHECK(p != ".");
}
