// A shared library that is not a mechgraph plugin: it exports no entry.
extern "C" __attribute__((visibility("default"))) int mechgraph_test_not_a_plugin() { return 42; }
