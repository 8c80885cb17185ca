# `cmake --install` puts Penumbra's libraries, their public headers, a CMake package and
# pkg-config files in a prefix (docs/embedding.md):
#   find_package(Penumbra CONFIG REQUIRED)                        all four components
#   find_package(Penumbra CONFIG REQUIRED COMPONENTS shadows)     only the engine-facing core
# gives Penumbra::shadows (the techniques on the caller's GL context: epoxy, glm, fmt),
# Penumbra::scenes (built-in scenes, scene files, glTF and OBJ: + libjpeg-turbo, Draco,
# meshoptimizer), Penumbra::reference (the Embree ground truth and its metrics) and
# Penumbra::bake (the distance-field bake for the sdf filter). Each component is its own export
# set, so linking Penumbra::shadows never asks for a model decoder, Embree or TBB.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(PENUMBRA_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Penumbra)

# component → its floors (bottom up), in the order a linker wants them reversed
set(PENUMBRA_COMPONENT_shadows penumbra_base penumbra_gl penumbra_scene penumbra_frame penumbra_techniques penumbra_core)
set(PENUMBRA_COMPONENT_reference penumbra_reference)
set(PENUMBRA_COMPONENT_bake penumbra_bake)
set(PENUMBRA_COMPONENT_scenes penumbra_sceneio)

foreach(component shadows scenes reference bake)
  install(TARGETS ${PENUMBRA_COMPONENT_${component}} EXPORT Penumbra_${component}
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(EXPORT Penumbra_${component} NAMESPACE Penumbra:: FILE Penumbra_${component}Targets.cmake
          DESTINATION ${PENUMBRA_CMAKE_DIR})
  foreach(floor IN LISTS PENUMBRA_COMPONENT_${component})
    get_target_property(sources ${floor} SOURCES)
    foreach(source IN LISTS sources)
      if(source MATCHES "/include/penumbra/[^/]+\\.h$")
        install(FILES ${source} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/penumbra)
      endif()
    endforeach()
  endforeach()
endforeach()

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/PenumbraConfig.cmake.in
  ${PROJECT_BINARY_DIR}/PenumbraConfig.cmake INSTALL_DESTINATION ${PENUMBRA_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/PenumbraConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/PenumbraConfig.cmake ${PROJECT_BINARY_DIR}/PenumbraConfigVersion.cmake
        DESTINATION ${PENUMBRA_CMAKE_DIR})

# pkg-config: penumbra (the core), penumbra-scenes and penumbra-reference; static archives, most
# dependent first.
# Relocatable: the prefix is found from the .pc file's own folder, so `cmake --install --prefix`
# anywhere gives files that point at that prefix.
file(RELATIVE_PATH PENUMBRA_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
set(PENUMBRA_PC_LIBS "-lpenumbra_core -lpenumbra_techniques -lpenumbra_frame -lpenumbra_scene -lpenumbra_gl -lpenumbra_base")
configure_file(${PROJECT_SOURCE_DIR}/cmake/penumbra.pc.in ${PROJECT_BINARY_DIR}/penumbra.pc @ONLY)
foreach(pc penumbra-scenes penumbra-reference)
  configure_file(${PROJECT_SOURCE_DIR}/cmake/${pc}.pc.in ${PROJECT_BINARY_DIR}/${pc}.pc @ONLY)
endforeach()
install(FILES ${PROJECT_BINARY_DIR}/penumbra.pc ${PROJECT_BINARY_DIR}/penumbra-scenes.pc
              ${PROJECT_BINARY_DIR}/penumbra-reference.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
