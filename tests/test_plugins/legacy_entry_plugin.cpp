// A plugin as ABI 3 and older declared its entry (a Boost.DLL alias named `mechgraph_plugin`): the
// host must say it was built for an older mechgraph instead of "not a plugin".
extern "C" __attribute__((visibility("default"))) void* mechgraph_plugin = nullptr;
