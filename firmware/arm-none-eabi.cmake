# CMake toolchain file for Debian's bare-metal Arm compiler (apt: gcc-arm-none-eabi, libnewlib-arm-none-eabi,
# libstdc++-arm-none-eabi-newlib). The core (-mcpu) is chosen per target in firmware/CMakeLists.txt, so one
# build tree holds the cortex-m0plus, cortex-m4 and cortex-m3 (qemu) images side by side.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

set(TRIONET_ARM_PREFIX "arm-none-eabi-" CACHE STRING "Prefix of the bare-metal Arm tools")
set(CMAKE_C_COMPILER ${TRIONET_ARM_PREFIX}gcc)
set(CMAKE_CXX_COMPILER ${TRIONET_ARM_PREFIX}g++)
set(CMAKE_ASM_COMPILER ${TRIONET_ARM_PREFIX}gcc)
find_program(TRIONET_ARM_NM ${TRIONET_ARM_PREFIX}nm REQUIRED)
find_program(TRIONET_ARM_SIZE ${TRIONET_ARM_PREFIX}size REQUIRED)

# The compiler check cannot link without a linker script and startup code: compile only.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
