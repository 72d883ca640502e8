# Cross-compiling for 64-bit Windows with Debian's MinGW-w64 (posix threads):
#   cmake -DCMAKE_TOOLCHAIN_FILE=cmake/mingw-w64.cmake ...
# tools/release uses it; it installs g++-mingw-w64-x86-64-posix.
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
set(SCAFFOLD_MINGW_TRIPLET x86_64-w64-mingw32)

set(CMAKE_C_COMPILER ${SCAFFOLD_MINGW_TRIPLET}-gcc-posix)
set(CMAKE_CXX_COMPILER ${SCAFFOLD_MINGW_TRIPLET}-g++-posix)
set(CMAKE_RC_COMPILER ${SCAFFOLD_MINGW_TRIPLET}-windres)

# Libraries and headers for Windows (libz-mingw-w64-dev's zlib among them)
# come from the MinGW sysroot only; programs run at build time from the host.
set(CMAKE_FIND_ROOT_PATH /usr/${SCAFFOLD_MINGW_TRIPLET})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# One self-contained .exe: no libstdc++/libgcc/winpthread DLLs beside it,
# and static libraries (libz.a, not the import library libz.dll.a). No link
# time stamp in the PE header: the same source gives the same bytes.
set(CMAKE_FIND_LIBRARY_SUFFIXES .a)
set(ZLIB_USE_STATIC_LIBS ON)
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static -static-libgcc -static-libstdc++ -Wl,--no-insert-timestamp")
# Release programs are stripped by the linker (strip run afterwards would
# stamp the PE header with the time again): the tests run what is shipped.
set(CMAKE_EXE_LINKER_FLAGS_RELEASE_INIT "-s")
