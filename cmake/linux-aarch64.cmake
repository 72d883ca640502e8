# 64-bit ARM Linux (Raspberry Pi OS 64-bit, arm64): g++-aarch64-linux-gnu.
set(SCAFFOLD_CROSS_TRIPLET aarch64-linux-gnu)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
include(${CMAKE_CURRENT_LIST_DIR}/linux-cross.cmake)
