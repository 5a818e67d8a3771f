# Included by firmware/CMakeLists.txt. The lab's board programs (scripts/lab): the Trio manual's Example 2 on emulated Cortex-M3 boards
# (qemu-system-arm -M lm3s6965evb), wired into a ring by `trionet ring wire` (docs/firmware.md, "The lab").
#
# The wire parameters come from a profile header, `trionet profile header --namespace lab_profile`:
# TRIONET_LAB_PROFILE_DIR holds its lab_profile.hpp. By default the default profile's header, committed in
# profile/ (a test checks that it is what the tool writes); scripts/lab builds the images again with the
# header of another profile in a build tree of their own.
set(TRIONET_LAB_PROFILE_DIR ${CMAKE_CURRENT_LIST_DIR}/profile CACHE PATH
    "Directory of the lab_profile.hpp the lab's board images are built with")

foreach(program master axis)
  trionet_firmware(lab-${program}-cortex-m3 cortex-m3 0 ${CMAKE_CURRENT_LIST_DIR}/${program}.cpp)
  target_include_directories(lab-${program}-cortex-m3 PRIVATE ${CMAKE_CURRENT_LIST_DIR} ${TRIONET_LAB_PROFILE_DIR})
endforeach()
