# mechgraph_add_plugin(NAME source...): a plugin is one MODULE library in the build's plugin
# folder, linked against libmechgraph, exporting only its handshake entry.
function(mechgraph_add_plugin name)
  add_library(${name} MODULE ${ARGN})
  target_link_libraries(${name} PRIVATE mechgraph::core)
  set_target_properties(${name} PROPERTIES
    PREFIX "mechgraph_"
    LIBRARY_OUTPUT_DIRECTORY "${MECHGRAPH_PLUGIN_OUTPUT_DIR}")
endfunction()
