# cmake --install: pkm::kinematics (the static library and the headers of core/, machine/ and kinematics/ under
# include/pkm/, so that #include "machine/hexapod.hpp" works), the export set pkmTargets and pkmConfig.cmake.
# A consumer: find_package(pkm REQUIRED) and target_link_libraries(app PRIVATE pkm::kinematics); it needs Eigen
# only (examples/consumer/, docs/libraries.md).
include(CMakePackageConfigHelpers)
set(PKM_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/pkm)

install(TARGETS pkm_kinematics EXPORT pkmTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(folder core machine kinematics)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/${folder} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/pkm
          FILES_MATCHING PATTERN "*.hpp")
endforeach()
install(EXPORT pkmTargets NAMESPACE pkm:: DESTINATION ${PKM_INSTALL_CMAKEDIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/pkmConfig.cmake.in ${PROJECT_BINARY_DIR}/pkmConfig.cmake
                              INSTALL_DESTINATION ${PKM_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/pkmConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/pkmConfig.cmake ${PROJECT_BINARY_DIR}/pkmConfigVersion.cmake
        DESTINATION ${PKM_INSTALL_CMAKEDIR})
