// mechgraph plugin-test (LIB.so | TYPE)... [--set TYPE.PARAM=VALUE ...] [--continuity TYPE=N] [--json]:
// the conformance suites (sdk/include/mechgraph/testing/) against every node type of a plugin file,
// or against named types, each evaluated with its own declared defaults. Handle inputs (an object of
// the kind a node takes) come from another loaded type that makes one from its defaults alone.
#include "cli.hpp"
#include <mechgraph/host/terminal_output.hpp>
#include "options.hpp"

#include <mechgraph/did_you_mean.hpp>
#include <mechgraph/json_writer.hpp>
#include <mechgraph/testing/node_conformance.hpp>

#include <spdlog/spdlog.h>

#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

namespace mechgraph::cli {
namespace {

using testing::Check;

// A value for a handle input: the first loaded type (by name) that makes an object of that kind from
// its defaults and examples, its own handle inputs made the same way (an object from another kind's
// object, ...), to a depth of four. Made once per kind.
class InputProvider {
 public:
  explicit InputProvider(const PluginRegistry& registry) : registry_(registry) {}
  std::optional<Value> operator()(const PortSpec& port) { return make(port, 0); }

 private:
  std::optional<Value> make(const PortSpec& port, int depth) {
    if (port.kind != ValueKind::handle || depth > 4) return std::nullopt;
    if (auto it = made_.find(port.handle_kind); it != made_.end()) return it->second;
    if (!in_progress_.insert(port.handle_kind).second) return std::nullopt;  // a cycle of kinds
    std::optional<Value> found;
    for (const std::string& name : registry_.type_names()) {
      const NodeType& type = *registry_.find(name)->type;
      const NodeInfo& info = type.info();
      const PortSpec* out = nullptr;
      for (const PortSpec& o : info.outputs)
        if (o.kind == ValueKind::handle && o.handle_kind == port.handle_kind && !info.effect_of_output(o.name)) out = &o;
      if (!out) continue;
      try {
        InputSet inputs;
        bool complete = true;
        for (const PortSpec& in : info.inputs) {
          if (in.optional) continue;
          const auto v = make(in, depth + 1);
          if (!v) complete = false;
          else inputs.add(in.name, *v);
        }
        if (!complete) continue;
        const auto run = testing::run_node(type, testing::params_with_defaults(info), inputs);
        if (auto it = run.outputs.all().find(out->name); it != run.outputs.all().end()) {
          spdlog::info("input '{}' ({}) from {} with its defaults", port.name, port.handle_kind, name);
          found = it->second;
          break;
        }
      } catch (const std::exception&) {
        continue;  // this one cannot make it from its defaults: try the next
      } catch (...) {
        // Not a std::exception: a defect of that plugin, which its own test reports; try the next.
        spdlog::warn("{} threw something that is not a std::exception while making a {} from its defaults", name,
                     port.handle_kind);
        continue;
      }
    }
    in_progress_.erase(port.handle_kind);
    made_[port.handle_kind] = found;
    return found;
  }

  const PluginRegistry& registry_;
  std::map<std::string, std::optional<Value>> made_;
  std::set<std::string> in_progress_;
};

const char* status_name(Check::Status s) {
  return s == Check::Status::passed ? "passed" : s == Check::Status::failed ? "failed" : "skipped";
}

}  // namespace

int plugin_test_command(const GlobalOptions& g, const std::vector<std::string>& args) {
  constexpr const char* synopsis =
      "mechgraph plugin-test (LIB.so | TYPE)... [--set TYPE.PARAM=VALUE ...] [--continuity TYPE=N] [--strict] [--threads N] [--json]";
  po::options_description visible("plugin-test options");
  visible.add_options()("help,h", "this text")
      ("set", po::value<std::vector<std::string>>()->composing(),
       "a parameter of one type for the test, as in a scene: --set mytype.length=8mm")
      ("continuity", po::value<std::vector<std::string>>()->composing(),
       "cam laws of TYPE must be continuous up to derivative N at breakpoints (0 lift, 1 velocity, 2 acceleration, 3 jerk;"
       " default 0): --continuity cam.cycloidal=2")
      ("threads", po::value<int>()->default_value(4), "evaluations at once in the thread-safety check (0: skip it)")
      ("strict", "a type that cannot be evaluated with its defaults and examples fails (else it is skipped)")
      ("json", "the checks as JSON");
  po::options_description all;
  all.add(visible).add_options()("target", po::value<std::vector<std::string>>()->required(), "plugin file or node type");
  po::positional_options_description positional;
  positional.add("target", -1);
  po::variables_map vm;
  if (!parse_options(args, visible, all, positional, vm, synopsis)) return ok;

  // Plugin files named on the command line load first, so the file under test wins over an
  // installed copy of the same plugin (that one is skipped); a refused file is a PluginError (exit 4).
  // They go through the registry's checks and crash probe like any other plugin file (a bare name
  // is made absolute there, so the probe loads the very file given).
  const auto targets = vm["target"].as<std::vector<std::string>>();
  std::vector<std::filesystem::path> files;
  for (const std::string& target : targets) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(target, ec)) files.push_back(std::filesystem::absolute(target, ec));
  }
  // Every SDK 1.x type is checked through the C boundary, the one a host of another compiler or
  // release uses; a type this host would otherwise call as itself (one C++ layer, node_cxx.h) is
  // the plugin's C++ class, which the plugin's own tests check with the same kit.
  GlobalOptions through_c = g;
  through_c.node_types_through_c = true;
  PluginRegistry registry = load_plugins(through_c, files);
  std::vector<std::string> types;
  for (const std::string& target : targets) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(target, ec)) {
      const PluginInfo* plugin = nullptr;
      for (const PluginInfo& p : registry.plugins())
        if (std::filesystem::equivalent(p.path, target, ec)) plugin = &p;
      if (!plugin) throw PluginError("plugin '" + target + "' was not loaded");
      spdlog::info("plugin '{}' {} from {}: {} node types", plugin->id, plugin->version, plugin->path.string(),
                   plugin->node_types.size());
      types.insert(types.end(), plugin->node_types.begin(), plugin->node_types.end());
    } else if (registry.find(target)) {
      types.push_back(target);
    } else {
      throw UsageError("'" + target + "' is neither a plugin file nor a loaded node type; " +
                       unknown_name_message("node type", target, registry.type_names()));
    }
  }

  const int threads = vm["threads"].as<int>();
  if (threads < 0 || threads > testing::max_check_threads)
    throw UsageError("--threads must be from 0 (skip the thread-safety check) to " +
                     std::to_string(testing::max_check_threads) + ", got " + std::to_string(threads));
  std::map<std::string, testing::NodeCheckOptions> options;
  for (const std::string& t : types) options[t].threads = threads;
  if (vm.count("set"))
    for (const std::string& s : vm["set"].as<std::vector<std::string>>()) {
      const auto eq = s.find('=');
      const auto dot = s.rfind('.', eq);
      if (eq == std::string::npos || dot == std::string::npos || dot == 0)
        throw UsageError("--set " + s + ": expected TYPE.PARAM=VALUE, e.g. --set mytype.length=8mm");
      const std::string type = s.substr(0, dot);
      if (!options.count(type)) throw UsageError("--set " + s + ": " + unknown_name_message("node type under test", type, types));
      options[type].values[s.substr(dot + 1, eq - dot - 1)] = s.substr(eq + 1);
    }
  if (vm.count("continuity"))
    for (const std::string& s : vm["continuity"].as<std::vector<std::string>>()) {
      const auto eq = s.find('=');
      const std::string type = s.substr(0, eq);
      int order = -1;
      try {
        order = eq == std::string::npos ? -1 : std::stoi(s.substr(eq + 1));
      } catch (const std::exception&) {
      }
      if (order < 0 || order > 3) throw UsageError("--continuity " + s + ": expected TYPE=N with N from 0 to 3");
      if (!options.count(type)) throw UsageError("--continuity " + s + ": " + unknown_name_message("node type under test", type, types));
      options[type].cam_law.continuity = order;
    }

  InputProvider provider(registry);
  int failed = 0;
  JsonWriter json(std::cout);
  const bool as_json = vm.count("json") > 0;
  if (as_json) json.begin_object().key("types").begin_array();
  for (const std::string& t : types) {
    testing::NodeCheckOptions& o = options[t];
    o.input_for = [&provider](const PortSpec& p) { return provider(p); };
    testing::Report report;
    try {
      report = testing::check_node_type(*registry.find(t)->type, o);
    } catch (const std::exception& e) {
      // The kit guards its own calls; what escapes it still fails the type, never the host.
      report.add("node " + t, testing::evaluation_check, false, std::string("threw: ") + e.what());
    } catch (...) {
      report.add("node " + t, testing::evaluation_check, false,
                 "threw something that is not a std::exception (a defect of its plugin)");
    }
    failed += report.failed();
    // --strict: a type the suites could not evaluate counts as a failure.
    bool evaluated = false;
    for (const Check& c : report.checks()) evaluated = evaluated || c.name == testing::evaluation_check;
    if (vm.count("strict") && !evaluated) {
      ++failed;
      spdlog::error("{}: not evaluated (--strict): give its required parameters defaults or examples", t);
    }
    if (as_json) {
      json.begin_object().key("type").value(t).key("passed").value(report.passed()).key("checks").begin_array();
      for (const Check& c : report.checks())
        json.begin_object().key("suite").value(c.suite).key("check").value(c.name).key("status").value(status_name(c.status))
            .key("detail").value(c.detail).end_object();
      json.end_array().end_object();
    } else {
      // The checks' details quote the plugin's text: shown through terminal_text.
      std::ostringstream text;
      text << report.str() << t << ": " << report.count(Check::Status::passed) << " passed, " << report.failed() << " failed, "
           << report.count(Check::Status::skipped) << " skipped\n\n";
      print_text(text.str());
    }
  }
  if (as_json) {
    json.end_array().key("failed").value(static_cast<double>(failed)).end_object();
    std::cout << "\n";
  }
  if (failed > 0) spdlog::error("{} conformance check(s) failed", failed);
  return failed > 0 ? conformance_failed : ok;
}

}  // namespace mechgraph::cli
