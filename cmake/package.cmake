# make package: a Debian package of everything cmake --install installs (the pkm command with its man page and
# completion, the libraries with their headers and CMake package), by CPack, into /usr. Its dependencies are
# the shared libraries the command links (dpkg-shlibdeps) and the development packages the CMake package needs.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME pkm)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "the pkm authors")
set(CPACK_PACKAGE_CONTACT "the pkm authors")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "kinematics, motion planning and analysis for parallel-kinematic machines")
string(CONCAT CPACK_PACKAGE_DESCRIPTION
       "pkm plans, executes and analyses motion for parallel-kinematic machine tools (hexapods, tripods, tricepts, "
       "planar mechanisms, glides): G-code and CAM CL data in, actuator motion within every limit out, with drive "
       "forces, stiffness, servo error and calibration.")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The Python module needs numpy; find_package(pkm) needs the development packages of the components asked for
# (cmake/pkmConfig.cmake.in).
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS
    "python3-numpy, libeigen3-dev, libyaml-cpp-dev, libfmt-dev, nlohmann-json3-dev, libnlopt-cxx-dev, libboost-dev, cmake")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "linuxcnc-uspace")
include(CPack)
