# The libraries for the cross builds (Windows: cmake/mingw-w64.cmake; the
# Raspberry Pi's Linux: cmake/linux-*.cmake), which Debian has no packages
# of for those targets (MinGW) or which would need foreign-architecture
# -dev packages of the whole of Boost:
# - Boost.Program_options: its compiled part built here as a static library
#   from Debian's own source package, unpacked by tools/release into
#   SCAFFOLD_BOOST_SOURCE_DIR (`apt-get source boost1.74`);
# - Boost's other headers, spdlog and fmt: Debian's headers in /usr/include,
#   header-only. They are reached through links in the build tree, so that
#   /usr/include itself (glibc's headers) never enters the search path.
set(SCAFFOLD_BOOST_SOURCE_DIR "" CACHE PATH "Debian's boost source tree (tools/release fetches it)")
if(NOT EXISTS "${SCAFFOLD_BOOST_SOURCE_DIR}/libs/program_options/src/cmdline.cpp")
  message(FATAL_ERROR "SCAFFOLD_BOOST_SOURCE_DIR='${SCAFFOLD_BOOST_SOURCE_DIR}' is not a boost source tree; "
                      "tools/release fetches one (apt-get source boost1.74)")
endif()

set(host_include "${CMAKE_BINARY_DIR}/host-include")
file(MAKE_DIRECTORY "${host_include}")
foreach(dir boost spdlog fmt)
  if(NOT EXISTS "/usr/include/${dir}")
    message(FATAL_ERROR "/usr/include/${dir} is missing (tools/deps installs libboost-dev, libspdlog-dev, libfmt-dev)")
  endif()
  file(CREATE_LINK "/usr/include/${dir}" "${host_include}/${dir}" SYMBOLIC)
endforeach()

add_library(Boost::boost INTERFACE IMPORTED)
target_include_directories(Boost::boost SYSTEM INTERFACE
  "${SCAFFOLD_BOOST_SOURCE_DIR}/libs/program_options/include" "${host_include}")
# No auto-linking pragmas (MSVC only anyway), and a static library.
target_compile_definitions(Boost::boost INTERFACE BOOST_ALL_NO_LIB BOOST_PROGRAM_OPTIONS_STATIC_LINK
  BOOST_ALLOW_DEPRECATED_HEADERS)  # quiet: Boost.Math 1.74 includes its own deprecated headers

file(GLOB boost_po_sources "${SCAFFOLD_BOOST_SOURCE_DIR}/libs/program_options/src/*.cpp")
add_library(boost_program_options STATIC ${boost_po_sources})
target_link_libraries(boost_program_options PUBLIC Boost::boost)
target_compile_options(boost_program_options PRIVATE -w)  # not our code: its warnings are Boost's
add_library(Boost::program_options ALIAS boost_program_options)

# Debian's spdlog is configured for an external fmt (SPDLOG_FMT_EXTERNAL in
# its tweakme.h); both are used header-only (no SPDLOG_COMPILED_LIB).
add_library(spdlog::spdlog INTERFACE IMPORTED)
target_include_directories(spdlog::spdlog SYSTEM INTERFACE "${host_include}")
target_compile_definitions(spdlog::spdlog INTERFACE SPDLOG_FMT_EXTERNAL FMT_HEADER_ONLY)

# zlib for a Linux target: Debian's multiarch zlib1g-dev:<arch> (its
# libz.a in /usr/lib/<triplet>; zlib.h and zconf.h are the same for every
# architecture), its headers linked in like the others.
if(NOT WIN32)
  foreach(h zlib.h zconf.h)
    file(CREATE_LINK "/usr/include/${h}" "${host_include}/${h}" SYMBOLIC)
  endforeach()
  set(ZLIB_INCLUDE_DIR "${host_include}" CACHE PATH "" FORCE)
  set(ZLIB_LIBRARY "/usr/lib/${SCAFFOLD_CROSS_TRIPLET}/libz.a" CACHE FILEPATH "" FORCE)
  if(NOT EXISTS "${ZLIB_LIBRARY}")
    message(FATAL_ERROR "${ZLIB_LIBRARY} is missing (tools/release installs zlib1g-dev for the target's architecture)")
  endif()
endif()


# minizip (.gcode.3mf) from Debian's source package for every cross build,
# reached as <minizip/unzip.h> like
# libminizip-dev's headers on Linux.
set(SCAFFOLD_MINIZIP_SOURCE_DIR "" CACHE PATH "Debian's minizip source tree (tools/release fetches it)")
if(NOT EXISTS "${SCAFFOLD_MINIZIP_SOURCE_DIR}/unzip.c")
  message(FATAL_ERROR "SCAFFOLD_MINIZIP_SOURCE_DIR='${SCAFFOLD_MINIZIP_SOURCE_DIR}' is not a minizip source tree; "
                      "tools/release fetches one (apt-get source minizip)")
endif()
enable_language(C)
find_package(ZLIB REQUIRED)
set(minizip_include "${CMAKE_BINARY_DIR}/minizip-include")
file(MAKE_DIRECTORY "${minizip_include}")
file(CREATE_LINK "${SCAFFOLD_MINIZIP_SOURCE_DIR}" "${minizip_include}/minizip" SYMBOLIC)
add_library(minizip STATIC "${SCAFFOLD_MINIZIP_SOURCE_DIR}/ioapi.c" "${SCAFFOLD_MINIZIP_SOURCE_DIR}/unzip.c"
  "${SCAFFOLD_MINIZIP_SOURCE_DIR}/zip.c")
target_include_directories(minizip SYSTEM PUBLIC "${minizip_include}")
target_link_libraries(minizip PUBLIC ZLIB::ZLIB)
target_compile_options(minizip PRIVATE -w)  # not our code
add_library(minizip::minizip ALIAS minizip)
