# mastrom_warnings(target): the project's warning flags; errors in CI (MASTROM_WERROR=ON).
function(mastrom_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic
                         $<$<BOOL:${MASTROM_WERROR}>:-Werror>)
endfunction()

# mastrom_library(name DEPS ...): a static library from every .cpp in the current folder.
# Sources are globbed so that adding a file needs no CMake edit.
function(mastrom_library name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  file(GLOB srcs CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  if(NOT srcs)  # a layer with no sources yet is header-only
    add_library(${name} INTERFACE)
    target_include_directories(${name} INTERFACE ${PROJECT_SOURCE_DIR})
    target_link_libraries(${name} INTERFACE ${ARG_DEPS})
    return()
  endif()
  add_library(${name} STATIC ${srcs})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PUBLIC ${ARG_DEPS})
  mastrom_warnings(${name})
endfunction()
