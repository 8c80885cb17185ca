# Penumbra's floors (docs/design.md): one static library per floor, each seeing only the headers
# of the floors it declares. The build enforces it with include roots: every floor gets its own
# folder under ${PROJECT_BINARY_DIR}/floors/<target>/ holding links to its own source folders
# ("scene" -> src/scene) and to its public headers ("penumbra/Scene.h" -> include/penumbra/
# Scene.h). A floor's include path is its own root plus the roots of the floors it links, so
# `#include "renderer/Renderer.h"` or `#include <penumbra/Renderer.h>` from a floor below the
# renderer finds no such file: a build error, not a review comment.
#
# penumbra_floor(<target>
#   DIRS <folders under src/>              sources: every .cpp/.h below them (recursively)
#   [HEADERS <names under include/penumbra/>]  the floor's public headers (installed)
#   [SOURCES <extra sources>]
#   [INCLUDE_ROOTS <folders>]              extra include roots it owns (PUBLIC; e.g. shaders/)
#   [DEPS <targets>]                       floors and libraries its headers need (PUBLIC)
#   [PRIVATE_DEPS <targets>])              what only its .cpp files use

function(penumbra_floor target)
  cmake_parse_arguments(PARSE_ARGV 1 F "" "" "DIRS;HEADERS;SOURCES;INCLUDE_ROOTS;DEPS;PRIVATE_DEPS")
  set(root ${PROJECT_BINARY_DIR}/floors/${target})
  file(MAKE_DIRECTORY ${root}/penumbra)
  set(sources ${F_SOURCES})
  foreach(dir IN LISTS F_DIRS)
    set(src ${PROJECT_SOURCE_DIR}/src/${dir})
    if(NOT IS_DIRECTORY ${src})
      message(FATAL_ERROR "penumbra_floor(${target}): src/${dir} is not a folder")
    endif()
    file(GLOB_RECURSE found CONFIGURE_DEPENDS ${src}/*.cpp ${src}/*.h)
    list(APPEND sources ${found})
    get_filename_component(parent ${root}/${dir} DIRECTORY)
    file(MAKE_DIRECTORY ${parent})
    file(CREATE_LINK ${src} ${root}/${dir} SYMBOLIC)
  endforeach()
  set(public_headers)
  foreach(header IN LISTS F_HEADERS)
    set(path ${PROJECT_SOURCE_DIR}/include/penumbra/${header})
    if(NOT EXISTS ${path})
      message(FATAL_ERROR "penumbra_floor(${target}): include/penumbra/${header} does not exist")
    endif()
    file(CREATE_LINK ${path} ${root}/penumbra/${header} SYMBOLIC)
    list(APPEND public_headers ${path})
  endforeach()
  set_property(GLOBAL APPEND PROPERTY PENUMBRA_PUBLIC_HEADERS ${public_headers})

  add_library(${target} STATIC ${sources} ${public_headers})
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${root}> $<INSTALL_INTERFACE:include>)
  foreach(extra IN LISTS F_INCLUDE_ROOTS)
    target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${extra}>)
  endforeach()
  target_link_libraries(${target} PUBLIC ${F_DEPS} PRIVATE $<BUILD_INTERFACE:penumbra_warnings> ${F_PRIVATE_DEPS})
endfunction()

# Fails the configuration when `target`'s link closure (what a program linking it links) holds
# one of `forbidden` (target names or link items): e.g. the engine-facing library must never
# bring a windowing system or the ray tracer with it.
function(penumbra_check_link_closure target)
  set(forbidden ${ARGN})
  set(queue ${target})
  set(seen)
  while(queue)
    list(POP_FRONT queue item)
    if(item IN_LIST seen)
      continue()
    endif()
    list(APPEND seen ${item})
    # $<LINK_ONLY:x> and $<BUILD_INTERFACE:x> still link x; $<INSTALL_INTERFACE:...> is not built here.
    string(REGEX REPLACE "^\\$<(LINK_ONLY|BUILD_INTERFACE):(.*)>$" "\\2" name "${item}")
    foreach(bad IN LISTS forbidden)
      if(name STREQUAL bad)
        message(FATAL_ERROR "${target} links ${bad} (through its dependencies); the engine-facing floors must not")
      endif()
    endforeach()
    if(TARGET ${name})
      get_target_property(aliased ${name} ALIASED_TARGET)
      if(aliased)
        list(APPEND queue ${aliased})
        continue()
      endif()
      get_target_property(type ${name} TYPE)
      get_target_property(interface ${name} INTERFACE_LINK_LIBRARIES)
      if(interface)
        list(APPEND queue ${interface})
      endif()
      if(type STREQUAL "STATIC_LIBRARY")
        get_target_property(linked ${name} LINK_LIBRARIES)
        if(linked)
          list(APPEND queue ${linked})
        endif()
      endif()
    endif()
  endwhile()
endfunction()
