# mechgraph_add_plugin(NAME [OUTPUT_DIRECTORY DIR] [NO_INSTALL] SOURCES...)
#
# A mechgraph plugin is one MODULE library named mechgraph_NAME.so, linked against mechgraph::sdk,
# compiled with the C++ standard mechgraph was built with (the host refuses another one) and with
# hidden visibility, so it exports its entry (MECHGRAPH_PLUGIN) and nothing else.
#  - OUTPUT_DIRECTORY: where the built plugin lands; default ${CMAKE_BINARY_DIR}/mechgraph-plugins
#    (or MECHGRAPH_PLUGIN_OUTPUT_DIR if set), the folder to give `mechgraph --plugin-dir`.
#  - `cmake --install` puts it in lib/mechgraph/plugins of the install prefix (mechgraph's own
#    library folder, MECHGRAPH_PLUGIN_INSTALL_DIR, e.g. lib/x86_64-linux-gnu/... under /usr):
#    with mechgraph's own prefix it becomes a built-in plugin, else add that folder to
#    MECHGRAPH_PLUGIN_PATH. NO_INSTALL leaves it out.
include_guard(GLOBAL)
include(GNUInstallDirs)

function(mechgraph_add_plugin name)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "NO_INSTALL" "OUTPUT_DIRECTORY" "SOURCES")
  set(sources ${ARG_SOURCES} ${ARG_UNPARSED_ARGUMENTS})
  if(NOT sources)
    message(FATAL_ERROR "mechgraph_add_plugin(${name}): no sources given")
  endif()
  if(ARG_OUTPUT_DIRECTORY)
    set(out "${ARG_OUTPUT_DIRECTORY}")
  elseif(MECHGRAPH_PLUGIN_OUTPUT_DIR)
    set(out "${MECHGRAPH_PLUGIN_OUTPUT_DIR}")
  else()
    set(out "${CMAKE_BINARY_DIR}/mechgraph-plugins")
  endif()
  add_library(${name} MODULE ${sources})
  target_link_libraries(${name} PRIVATE mechgraph::sdk)
  set_target_properties(${name} PROPERTIES
    PREFIX "mechgraph_"
    LIBRARY_OUTPUT_DIRECTORY "${out}"
    CXX_STANDARD 20
    CXX_STANDARD_REQUIRED ON
    CXX_EXTENSIONS OFF
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON
    INSTALL_RPATH "$ORIGIN/../.."
    # The same RUNPATH in the build tree: a build RUNPATH that differs from the install one gets a
    # trailing ':' from CMake (room to rewrite it at install), an empty entry the dynamic loader
    # reads as the current folder. In mechgraph's tree $ORIGIN/../.. is build/lib, as installed;
    # elsewhere the host has loaded libmechgraph before any plugin, so it is not searched for.
    BUILD_WITH_INSTALL_RPATH ON)
  # Every symbol resolved at link time (a missing one is a build error, not a load error), and no
  # symbols of static libraries re-exported. Sanitizer builds leave the runtime's symbols to the
  # program (clang links it into executables only), so they skip --no-undefined.
  target_link_options(${name} PRIVATE "LINKER:--exclude-libs,ALL")
  if(NOT CMAKE_CXX_FLAGS MATCHES "-fsanitize")
    target_link_options(${name} PRIVATE "LINKER:--no-undefined")
  endif()
  if(NOT ARG_NO_INSTALL)
    if(MECHGRAPH_PLUGIN_INSTALL_DIR)  # mechgraph's own layout (set by find_package or the tree)
      install(TARGETS ${name} LIBRARY DESTINATION ${MECHGRAPH_PLUGIN_INSTALL_DIR})
    else()
      install(TARGETS ${name} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/mechgraph/plugins)
    endif()
  endif()
endfunction()
