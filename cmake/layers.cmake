# The library as layered static libraries, one or more src/ folders each (docs/ARCHITECTURE.md). The folders'
# order is the order of the pkm_layer() calls below and of the folders within each: a file may include the
# headers of its own folder and of the folders before it only (scripts/include-order.py checks it in
# `make lint`, reading this file):
#
#   pkm_kinematics (pkm::kinematics)  core/ kinematics/ machine/ execution/: the kinematics and the real-time
#                                     executor (position-independent: LinuxCNC modules link it); PUBLIC
#                                     Eigen, Threads (fmt header-only)
#   pkm_io         (pkm::io)          io/                              PUBLIC kinematics, yaml-cpp, fmt, json
#   pkm_motion     (pkm::motion)      program/ path/ planning/ interpolation/: the motion core, from the part
#                                     program to the servo ticks and drive steps; PUBLIC io; PRIVATE NLopt
#   pkm_analysis   (pkm::analysis)    statics/ dynamics/ redundancy/ stiffness/ servo/ calibration/
#                                     workspace/ analyses/: what the machine does along the motion, the
#                                     run's analyses listening to its ticks; PUBLIC motion; PRIVATE NLopt,
#                                     Boost (headers), TBB
#   pkm_formats    (pkm::formats)     formats/: the files of each run; PUBLIC analysis
#   pkm_report     (pkm::report)      report/ (+ pkm_report_assets)    PUBLIC formats
#   pkm_pipeline   (pkm::pipeline)    pipeline/: the one orchestrator  PUBLIC report
#   pkm_lib        INTERFACE: all of them (the CLI, tests, bench and fuzz link this)

# PKM_UNITY_LIB compiles every layer in batches (the sanitizer build uses it to fit CI's time on 2 cores).
option(PKM_UNITY_LIB "Unity build of the library layers" OFF)
# 8 per batch is the fastest measured on CI's 2 cores: 16 made the sanitizer build slower (9 min against 7).
set(PKM_UNITY_BATCH 8 CACHE STRING "Source files per unity batch (PKM_UNITY_LIB, PKM_UNITY_TESTS)")

# pkm_layer(<target> <alias> <folder>...): a static library of the .cpp files in src/<folder>/.
function(pkm_layer target alias)
  set(sources)
  foreach(folder ${ARGN})
    file(GLOB folder_sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/${folder}/*.cpp)
    list(APPEND sources ${folder_sources})
  endforeach()
  add_library(${target} STATIC ${sources})
  add_library(pkm::${alias} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${alias})
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/src>)
  # The warning (and sanitizer) flags, not linked as a target: an installed layer does not depend on them.
  target_compile_options(${target} PRIVATE $<TARGET_PROPERTY:pkm_warnings,INTERFACE_COMPILE_OPTIONS>
                                           $<TARGET_PROPERTY:pkm_sanitized,INTERFACE_COMPILE_OPTIONS>)
  if(PKM_UNITY_LIB)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${PKM_UNITY_BATCH})
  endif()
endfunction()

# Eigen, fmt and yaml-cpp dominate compile time; precompiled per layer, they keep CI (a Release and a sanitizer
# build on 2 cores) within its budget. pkm_kinematics has its own (position-independent, fmt header-only); the
# layers above share pkm_io's, as they are compiled with the same flags.
set(PKM_LIB_PCH <Eigen/Core> <Eigen/Geometry> <Eigen/LU> <fmt/format.h> <string> <vector>)

# The kinematics: poses, mechanisms, IK/FK/Jacobians, analyses. No file I/O; position-independent, so that a
# shared object (a LinuxCNC real-time kinematics module) can link it. Its error messages use fmt header-only
# and privately, so that a consumer of the installed library needs Eigen only.
pkm_layer(pkm_kinematics kinematics core kinematics machine execution)
set_target_properties(pkm_kinematics PROPERTIES POSITION_INDEPENDENT_CODE ON)
target_include_directories(pkm_kinematics PUBLIC $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/pkm>)
target_include_directories(pkm_kinematics PRIVATE $<TARGET_PROPERTY:fmt::fmt,INTERFACE_INCLUDE_DIRECTORIES>)
target_compile_definitions(pkm_kinematics PRIVATE FMT_HEADER_ONLY)
# Threads: one all-modes solve may follow its homotopy paths on several threads (stewart_all_modes.cpp).
target_link_libraries(pkm_kinematics PUBLIC Eigen3::Eigen Threads::Threads)
target_precompile_headers(pkm_kinematics PRIVATE ${PKM_LIB_PCH})

# Input and output files: machine files (YAML), pose input, the guarded file reader, atomic outputs and sets.
pkm_layer(pkm_io io io)
target_link_libraries(pkm_io PUBLIC pkm_kinematics yaml-cpp fmt::fmt nlohmann_json::nlohmann_json)
target_precompile_headers(pkm_io PRIVATE ${PKM_LIB_PCH})
# The version of project() is the one place it is set: io/version.cpp gets it as its own definition (outside
# the unity batches, so that a new version recompiles one file).
set_source_files_properties(${PROJECT_SOURCE_DIR}/src/io/version.cpp PROPERTIES
  COMPILE_DEFINITIONS "PKM_VERSION=\"${PROJECT_VERSION}\"" SKIP_UNITY_BUILD_INCLUSION ON)

# The motion core: from part program to servo ticks and drive output. It knows no analysis: whatever wants
# the ticks listens (planning/tick_observer.hpp).
pkm_layer(pkm_motion motion program path planning interpolation interpolation/methods
          interpolation/quantisation interpolation/contour interpolation/drive_output)
# NLopt: the workspace excursion of a plan (planning/workspace_excursion.cpp).
target_link_libraries(pkm_motion PUBLIC pkm_io PRIVATE NLopt::nlopt)
target_precompile_headers(pkm_motion REUSE_FROM pkm_io)

# The analyses: statics, dynamics, redundancy, stiffness, servo, calibration, workspace, and the run's
# analyses as tick observers (analyses/).
pkm_layer(pkm_analysis analysis statics dynamics redundancy stiffness servo calibration workspace analyses)
# Boost.Odeint, headers only and only in .cpp files (elastic_simulation.cpp): no installed header needs it.
target_link_libraries(pkm_analysis PUBLIC pkm_motion PRIVATE NLopt::nlopt Boost::headers TBB::tbb)
target_precompile_headers(pkm_analysis REUSE_FROM pkm_io)

# The files each run writes (CSV, JSON summaries) from the values the computations return.
pkm_layer(pkm_formats formats formats)
target_link_libraries(pkm_formats PUBLIC pkm_analysis PRIVATE ${HDF5_LINK_LIBRARIES} ${LIBDEFLATE_LINK_LIBRARIES} ZLIB::ZLIB)
target_precompile_headers(pkm_formats REUSE_FROM pkm_io)
# HDF5's headers and definitions for the two files that include them (the writer and the reader), outside the
# shared precompiled header.
set_source_files_properties(${PROJECT_SOURCE_DIR}/src/formats/hdf5_table.cpp
  ${PROJECT_SOURCE_DIR}/src/formats/hdf5_table_reader.cpp PROPERTIES
  INCLUDE_DIRECTORIES "${HDF5_INCLUDE_DIRS}" COMPILE_OPTIONS "${HDF5_CFLAGS_OTHER}"
  SKIP_PRECOMPILE_HEADERS ON SKIP_UNITY_BUILD_INCLUSION ON)

# The HTML report of a run's output directory (the page itself: pkm_report_assets, cmake/report_assets.cmake).
pkm_layer(pkm_report report report)
target_link_libraries(pkm_report PUBLIC pkm_formats PRIVATE pkm_report_assets)
target_precompile_headers(pkm_report REUSE_FROM pkm_io)

# The CLI's whole runs (plan / interpolate a program, with the optional report): above the report.
pkm_layer(pkm_pipeline pipeline pipeline)
target_link_libraries(pkm_pipeline PUBLIC pkm_report)
target_precompile_headers(pkm_pipeline REUSE_FROM pkm_io)

add_library(pkm_lib INTERFACE)
target_link_libraries(pkm_lib INTERFACE pkm_pipeline pkm_report pkm_formats pkm_analysis pkm_motion pkm_io
                                          pkm_kinematics)

# The files with AVX2/FMA copies of their kernels (core/wide_kernels.hpp, chosen at run time) need their
# multiply–adds contracted into fused ones, which ISO C++ mode leaves off. The baseline x86-64 target has no
# fused instruction, so this changes nothing else in them. Out of the unity batches and the precompiled
# header, so that the option stays on these files alone. Not in the sanitizer build, which checks correctness
# (the copies there run without fused multiply–adds) and has CI's time to keep: there they stay in the batches.
if(NOT PKM_SANITIZE)
  set_source_files_properties(
    ${PROJECT_SOURCE_DIR}/src/kinematics/stewart_homotopy.cpp ${PROJECT_SOURCE_DIR}/src/dynamics/elastic_model.cpp
    ${PROJECT_SOURCE_DIR}/src/dynamics/rigid_terms.cpp ${PROJECT_SOURCE_DIR}/src/dynamics/fixed_base_struts.cpp
    PROPERTIES COMPILE_OPTIONS "-ffp-contract=fast" SKIP_UNITY_BUILD_INCLUSION ON SKIP_PRECOMPILE_HEADERS ON)
endif()
