# The plugin folder, in the install tree and in the build tree. Included before the
# subdirectories, so plugin targets can use voronoimesh_install_plugin().

# Relative to the install prefix: "voronoimesh/plugins" beside the installed library.
# vm::installed_plugin_dir() finds the same folder at run time from the library's own
# file, so an installed tree still finds its plugins after it is moved.
set(VORONOIMESH_INSTALL_PLUGINDIR "${CMAKE_INSTALL_LIBDIR}/voronoimesh/plugins")
# The same folder in the build tree (the library is built into BUILD/lib), where the
# built library looks for plugins built here.
set(VORONOIMESH_BUILD_PLUGINDIR "${PROJECT_BINARY_DIR}/${VORONOIMESH_INSTALL_PLUGINDIR}")

# Installs the shared-library target `target` into the plugin folder.
function(voronoimesh_install_plugin target)
  install(TARGETS ${target} LIBRARY DESTINATION ${VORONOIMESH_INSTALL_PLUGINDIR})
endfunction()
