# mechgraph_add_plugin(NAME [OUTPUT_DIRECTORY DIR] [NO_INSTALL] [PRE_1_0_ENTRY] SOURCES...)
#
# A mechgraph plugin is one MODULE library named mechgraph_NAME.so, linked against mechgraph::sdk,
# compiled with C++20 and with hidden visibility, so it exports its entry (MECHGRAPH_PLUGIN_1) and
# nothing else.
#  - The SDK's C++ authoring layer (the sources of libmechgraph_sdk's C++ helpers: the ParamSpec and
#    PortSpec builders, the interfaces' key functions, summarize, refuse_undercut, the numerics) is
#    compiled into the plugin by the plugin's own compiler, as OpenFX's Support library is: the
#    object library mechgraph::sdk_cxx, built once per project from the sources the package installs
#    (share/mechgraph/sdk-cxx), hidden. Only the C functions mg_* of libmechgraph_sdk.so.1 are
#    called across, so any C++20 compiler and standard library will do (clang++ -stdlib=libc++ into
#    the gcc-built host). It needs the Boost and Eigen headers (the numerics use them).
#    A test program that compiles the plugin's sources links mechgraph::sdk_cxx too.
#    Why not header-only: those sources are some 2,700 lines that use Boost.Math and Eigen's FFT;
#    inline, every translation unit of every plugin would compile them (and every SDK header would
#    pull in Boost). Compiled once per project, they cost a plugin project about 15 files once, and a
#    plugin only the helpers it reaches (--gc-sections).
#  - PRE_1_0_ENTRY: a plugin of the pre-1.0 entry (MECHGRAPH_PLUGIN, plugin_abi.hpp) shares C++
#    classes with the host: it calls libmechgraph_sdk's exported C++ helpers instead, and must be
#    built by the host's compiler and standard library.
#  - OUTPUT_DIRECTORY: where the built plugin lands; default ${CMAKE_BINARY_DIR}/mechgraph-plugins
#    (or MECHGRAPH_PLUGIN_OUTPUT_DIR if set), the folder to give `mechgraph --plugin-dir`.
#  - `cmake --install` puts it in lib/mechgraph/plugins of the install prefix (mechgraph's own
#    library folder, MECHGRAPH_PLUGIN_INSTALL_DIR, e.g. lib/x86_64-linux-gnu/... under /usr):
#    with mechgraph's own prefix it becomes a built-in plugin, else add that folder to
#    MECHGRAPH_PLUGIN_PATH. NO_INSTALL leaves it out.
include_guard(GLOBAL)
include(GNUInstallDirs)

# The sources of the SDK's C++ layer, one list for libmechgraph_sdk.so.1 (sdk/CMakeLists.txt) and
# for mechgraph::sdk_cxx; MECHGRAPH_SDK_CXX_SOURCE_DIR is sdk/src in mechgraph's tree and the
# installed copy in a package (mechgraphConfig.cmake). piece_points.hpp and decimal_number.hpp are
# their private headers.
set(MECHGRAPH_SDK_CXX_SOURCES
  dimension.cpp units.cpp node.cpp value.cpp bounded_read.cpp numerics_piecewise.cpp
  numerics_chebyshev.cpp tolerance.cpp cam_law.cpp cam_geometry.cpp cam_law_runs.cpp cam_curves.cpp
  interfaces.cpp block.cpp)
set(MECHGRAPH_SDK_CXX_PRIVATE_HEADERS piece_points.hpp decimal_number.hpp)

# mechgraph_sdk_cxx: the C++ layer as an OBJECT library of this project (once, whatever number of
# plugins), compiled by this project's compiler: position-independent, hidden, and with
# MECHGRAPH_SDK_CXX_IN_PLUGIN for it and for whatever links it (mechgraph/export.hpp: the layer's
# classes and functions are then hidden too, each plugin has its own copy and RTTI).
function(_mechgraph_sdk_cxx_library)
  if(TARGET mechgraph_sdk_cxx)
    return()
  endif()
  if(NOT TARGET Boost::headers)
    find_package(Boost 1.71)
  endif()
  if(NOT TARGET Eigen3::Eigen)
    find_package(Eigen3 3.3 NO_MODULE)
  endif()
  if(NOT TARGET Boost::headers OR NOT TARGET Eigen3::Eigen)
    message(FATAL_ERROR "mechgraph_add_plugin(): the SDK's C++ layer, which is compiled into each plugin, needs the "
                        "Boost (1.71 or later) and Eigen 3 headers (Debian: apt-get install libboost-dev libeigen3-dev)")
  endif()
  set(sources ${MECHGRAPH_SDK_CXX_SOURCES})
  list(TRANSFORM sources PREPEND "${MECHGRAPH_SDK_CXX_SOURCE_DIR}/")
  add_library(mechgraph_sdk_cxx OBJECT ${sources})
  target_link_libraries(mechgraph_sdk_cxx PUBLIC mechgraph::sdk PRIVATE Boost::headers Eigen3::Eigen)
  target_compile_definitions(mechgraph_sdk_cxx PUBLIC MECHGRAPH_SDK_CXX_IN_PLUGIN)
  # A section per function: a plugin's link keeps only the helpers it reaches (--gc-sections).
  # The SDK's finiteness checks (no NaN or infinity leaves a node) must hold whatever math flags
  # the plugin project uses for its own code: fast math would let the compiler drop them.
  target_compile_options(mechgraph_sdk_cxx PRIVATE -ffunction-sections -fdata-sections -fno-fast-math -fno-finite-math-only)
  set_target_properties(mechgraph_sdk_cxx PROPERTIES
    CXX_STANDARD 20
    CXX_STANDARD_REQUIRED ON
    CXX_EXTENSIONS OFF
    POSITION_INDEPENDENT_CODE ON
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  add_library(mechgraph::sdk_cxx ALIAS mechgraph_sdk_cxx)
endfunction()

function(mechgraph_add_plugin name)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "NO_INSTALL;PRE_1_0_ENTRY" "OUTPUT_DIRECTORY" "SOURCES")
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
  if(ARG_PRE_1_0_ENTRY)
    target_link_libraries(${name} PRIVATE mechgraph::sdk)
  else()
    _mechgraph_sdk_cxx_library()
    # The layer's objects are part of the plugin: every C++ helper binds inside it, also for the
    # static libraries a plugin links after this line, and only mg_* comes from libmechgraph_sdk.
    target_link_libraries(${name} PRIVATE mechgraph_sdk_cxx mechgraph::sdk)
    # The entry is all it exports: no weak symbol of a template (std::, Boost) leaves it either.
    set(exports "${CMAKE_BINARY_DIR}/CMakeFiles/mechgraph_plugin_exports.map")
    file(CONFIGURE OUTPUT "${exports}" CONTENT "{\n  global: mechgraph_plugin_entry_1;\n  local: *;\n};\n")
    target_link_options(${name} PRIVATE "LINKER:--version-script=${exports}" "LINKER:--gc-sections")
  endif()
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
