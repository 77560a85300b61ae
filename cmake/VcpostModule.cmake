# Helpers shared by the module folders: warnings and one library per module.

function(vcpost_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion)
  # GCC 12 at -O3 reports -Wrestrict inside std::string's own copy for plain
  # concatenations (a known false positive, GCC bug 105329).
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(${target} PRIVATE -Wno-restrict)
  endif()
  if(VCPOST_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# The repository's code includes its headers as "folder/file.h" from the
# source root. Every target that compiles such code adds the root for
# itself (PRIVATE): no module hands the whole tree on to its dependents.
function(vcpost_source_root target)
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR})
endfunction()

# vcpost_module(NAME <target> [DEPS <public deps>] [PRIVATE_DEPS <private deps>])
# Builds every .cpp of the calling folder (not its subfolders, which are
# modules of their own) into a static library; headers are included as
# "folder/file.h" from the source root (vcpost_source_root).
function(vcpost_module)
  cmake_parse_arguments(M "" "NAME" "DEPS;PRIVATE_DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  add_library(${M_NAME} STATIC ${sources})
  vcpost_source_root(${M_NAME})
  target_link_libraries(${M_NAME} PUBLIC ${M_DEPS} PRIVATE ${M_PRIVATE_DEPS})
  vcpost_warnings(${M_NAME})
endfunction()
