# cmake --install: the layers an outside project can link, as pkm:: targets of the export set pkmTargets, with
# the headers of their folders under include/pkm/ (so that #include "machine/hexapod.hpp" works) and
# pkmConfig.cmake:
#   pkm::kinematics  core/ kinematics/ machine/                 needs Eigen and the system's threads only
#   pkm::io          io/ (machine files and other inputs)       + yaml-cpp, fmt, nlohmann_json
#   pkm::motion      program/ path/ planning/ interpolation/    + NLopt
#   pkm::analysis    statics/ dynamics/ redundancy/ stiffness/ servo/ calibration/ workspace/ analyses/
#                                                               + NLopt, Boost headers, TBB
# A consumer: find_package(pkm REQUIRED [COMPONENTS kinematics io motion analysis]) and
# target_link_libraries(app PRIVATE pkm::motion); pkmConfig.cmake looks for the dependencies of the components
# asked for only (examples/consumer/, docs/libraries.md). The formats, the report and the pipeline stay inside
# the project.
include(CMakePackageConfigHelpers)
set(PKM_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/pkm)

install(TARGETS pkm_kinematics pkm_io pkm_motion pkm_analysis EXPORT pkmTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(folder core kinematics machine io program path planning interpolation statics dynamics redundancy stiffness servo
               calibration workspace analyses)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/${folder} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/pkm
          FILES_MATCHING PATTERN "*.hpp")
endforeach()
install(EXPORT pkmTargets NAMESPACE pkm:: DESTINATION ${PKM_INSTALL_CMAKEDIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/pkmConfig.cmake.in ${PROJECT_BINARY_DIR}/pkmConfig.cmake
                              INSTALL_DESTINATION ${PKM_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/pkmConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/pkmConfig.cmake ${PROJECT_BINARY_DIR}/pkmConfigVersion.cmake
        DESTINATION ${PKM_INSTALL_CMAKEDIR})
