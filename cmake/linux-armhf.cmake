# 32-bit ARM Linux, hard float (Raspberry Pi OS 32-bit, armhf):
# g++-arm-linux-gnueabihf. Debian's armhf is ARMv7 (Pi 2, 3, 4, 5, Zero 2);
# the ARMv6 boards (Pi 1, Zero, Zero W) cannot run it.
set(SCAFFOLD_CROSS_TRIPLET arm-linux-gnueabihf)
set(CMAKE_SYSTEM_PROCESSOR armv7l)
include(${CMAKE_CURRENT_LIST_DIR}/linux-cross.cmake)
