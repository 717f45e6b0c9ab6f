// A plugin really unloaded: with Lifetime::objects the library stays mapped exactly as long as the
// registry or something it made holds it, and is unmapped after (the test plugin is built with
// -fno-gnu-unique, so nothing pins it). An object that outlived its library would crash here.
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <dlfcn.h>
#include <unistd.h>

using namespace mechgraph;
using namespace mechgraph::testing;

namespace {

// Whether the library is mapped, without loading it (RTLD_NOLOAD takes a reference: give it back).
bool mapped(const std::filesystem::path& file) {
  void* handle = ::dlopen(file.c_str(), RTLD_NOW | RTLD_NOLOAD);
  if (handle) ::dlclose(handle);
  return handle != nullptr;
}

}  // namespace

TEST_CASE("a plugin is unloaded when the registry and every object it made are gone", "[plugins][lifetime]") {
  const std::filesystem::path file = test_plugin("test_arith_unloadable");
  REQUIRE_FALSE(mapped(file));
  std::shared_ptr<const DomainObject> survivor;
  std::shared_ptr<const NodeType> type_kept;
  {
    PluginRegistry registry(PluginRegistry::Lifetime::objects);
    registry.load_file(file);
    CHECK(mapped(file));
    const RegisteredType* box = registry.find("test.box");
    REQUIRE(box);
    InputSet in;
    in.add("x", Value::scalar(0.25));
    OutputSet out;
    RecordingContext ctx;
    box->type->evaluate(ParamSet{}, in, out, ctx);
    survivor = box->keep_alive(out.all().at("box").as_handle());
    type_kept = box->type;
  }
  // The registry is gone; a node type and an object the plugin made keep its code mapped.
  CHECK(mapped(file));
  CHECK(type_kept->info().type == "test.box");
  CHECK(survivor->kind() == "test_box");  // a virtual call into the plugin's code
  type_kept.reset();
  CHECK(mapped(file));
  survivor.reset();
  CHECK_FALSE(mapped(file));  // the last holder gone: unmapped
}

TEST_CASE("with the host's lifetime a plugin stays loaded after its registry", "[plugins][lifetime]") {
  // A copy, so that the library this test leaves loaded is not the one the test above unloads.
  const auto dir = std::filesystem::temp_directory_path() / ("mg_lifetime_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / "mechgraph_test_arith_unloadable.so";
  std::filesystem::copy_file(test_plugin("test_arith_unloadable"), file, std::filesystem::copy_options::overwrite_existing);
  {
    PluginRegistry registry;  // Lifetime::process
    registry.load_file(file);
  }
  CHECK(mapped(file));
  std::filesystem::remove_all(dir);
}
