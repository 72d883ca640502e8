# 32-bit ARM Linux, hard float (Raspberry Pi OS 32-bit, armhf):
# g++-arm-linux-gnueabihf. Debian's armhf is ARMv7 (Pi 2, 3, 4, 5, Zero 2);
# the ARMv6 boards (Pi 1, Zero, Zero W) cannot run it.
set(SCAFFOLD_CROSS_TRIPLET arm-linux-gnueabihf)
set(CMAKE_SYSTEM_PROCESSOR armv7l)
# GCC's notes that std::pair passing changed in GCC 7.1 (-Wpsabi) concern
# mixing objects built by GCC before 7.1: everything here is built at once.
set(SCAFFOLD_CROSS_FLAGS "-Wno-psabi")
include(${CMAKE_CURRENT_LIST_DIR}/linux-cross.cmake)
