# Static Linux programs for the Raspberry Pi (and other ARM boards), with
# Debian's cross compilers; cmake/linux-aarch64.cmake and
# cmake/linux-armhf.cmake set SCAFFOLD_CROSS_TRIPLET and include this.
# tools/release --linux-cross-only builds them.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_C_COMPILER ${SCAFFOLD_CROSS_TRIPLET}-gcc)
set(CMAKE_CXX_COMPILER ${SCAFFOLD_CROSS_TRIPLET}-g++)
set(CMAKE_LIBRARY_ARCHITECTURE ${SCAFFOLD_CROSS_TRIPLET})
# try_compile runs this file again without the cache: pass the triplet on.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES SCAFFOLD_CROSS_TRIPLET)

# The target's glibc and libstdc++ from the cross compiler's own sysroot;
# programs run at build time from the host.
set(CMAKE_FIND_ROOT_PATH /usr/${SCAFFOLD_CROSS_TRIPLET})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# The same output bytes as the x86-64 build: no fused multiply-add where
# the source has a multiply and an add (GCC fuses them by default on ARM;
# x86-64 without -march has no FMA to fuse into).
set(CMAKE_CXX_FLAGS_INIT "-ffp-contract=off ${SCAFFOLD_CROSS_FLAGS}")
set(CMAKE_C_FLAGS_INIT "-ffp-contract=off")
# One file that runs on any distribution (Raspberry Pi OS 32 or 64 bit,
# whatever its glibc): everything linked in. Stripped by the linker.
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static")
set(CMAKE_EXE_LINKER_FLAGS_RELEASE_INIT "-s")
