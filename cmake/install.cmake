# Installation: the shared library, its public headers, the CLI, an exported CMake
# package (find_package(voronoimesh CONFIG) -> voronoimesh::voronoimesh), a pkg-config
# file and the (initially empty) plugin folder; with VM_MPI also voronoimesh_mpi and
# mpi/distributed.hpp (find_package(voronoimesh CONFIG COMPONENTS mpi) -> voronoimesh::voronoimesh_mpi).
# See docs/api.md "Install and use the package".
include(CMakePackageConfigHelpers)

set(VORONOIMESH_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/voronoimesh")

install(TARGETS voronoimesh EXPORT voronoimeshTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
# mpi/distributed.hpp needs mpi.h and voronoimesh_mpi: a build without MPI installs neither.
if(VM_MPI)
  install(TARGETS voronoimesh_mpi EXPORT voronoimeshTargets LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  set(_vm_without_mpi_header "")
  set(VORONOIMESH_HAS_MPI TRUE) # the package's component mpi (voronoimeshConfig.cmake.in)
else()
  set(_vm_without_mpi_header PATTERN "mpi" EXCLUDE)
  set(VORONOIMESH_HAS_MPI FALSE)
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/libvoronoimesh/include/voronoimesh
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.hpp" PATTERN "*.h" ${_vm_without_mpi_header})
install(FILES ${PROJECT_BINARY_DIR}/include/voronoimesh/core/version.hpp
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/voronoimesh/core)
install(DIRECTORY DESTINATION ${VORONOIMESH_INSTALL_PLUGINDIR})

# The CLI finds the library relative to itself, so a moved prefix still runs.
file(RELATIVE_PATH _vm_bin_to_lib "${CMAKE_INSTALL_FULL_BINDIR}" "${CMAKE_INSTALL_FULL_LIBDIR}")
set_target_properties(voronoimesh_cli PROPERTIES INSTALL_RPATH "$ORIGIN/${_vm_bin_to_lib}")
install(TARGETS voronoimesh_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

install(EXPORT voronoimeshTargets NAMESPACE voronoimesh:: DESTINATION ${VORONOIMESH_INSTALL_CMAKEDIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/voronoimeshConfig.cmake.in
  ${PROJECT_BINARY_DIR}/voronoimeshConfig.cmake
  INSTALL_DESTINATION ${VORONOIMESH_INSTALL_CMAKEDIR}
  PATH_VARS VORONOIMESH_INSTALL_PLUGINDIR)
# While the major version is 0 every minor version may break the API (and the SONAME
# changes with it), so only the same MAJOR.MINOR is compatible.
if(PROJECT_VERSION_MAJOR EQUAL 0)
  set(_vm_compatibility SameMinorVersion)
else()
  set(_vm_compatibility SameMajorVersion)
endif()
write_basic_package_version_file(${PROJECT_BINARY_DIR}/voronoimeshConfigVersion.cmake
  COMPATIBILITY ${_vm_compatibility})
install(FILES ${PROJECT_BINARY_DIR}/voronoimeshConfig.cmake ${PROJECT_BINARY_DIR}/voronoimeshConfigVersion.cmake
  DESTINATION ${VORONOIMESH_INSTALL_CMAKEDIR})

# pkg-config: the prefix is found from the .pc file's own folder, so it is right
# wherever the tree is installed or moved.
file(RELATIVE_PATH _vm_pc_to_prefix "${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig" "${CMAKE_INSTALL_PREFIX}")
string(REGEX REPLACE "/$" "" _vm_pc_to_prefix "${_vm_pc_to_prefix}")
configure_file(${CMAKE_CURRENT_LIST_DIR}/voronoimesh.pc.in ${PROJECT_BINARY_DIR}/voronoimesh.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/voronoimesh.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
