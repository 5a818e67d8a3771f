# The tool's own capture against tshark: `trionet ring simulate example2 --pcap` writes a capture,
# `trionet ring decode --pcap --json` prints its view of every record, scripts/wireshark-compare checks that
# tshark with the dissectors shows the same fields. Arguments: TRIONET, PYTHON, SOURCE_DIR, WORK_DIR.
file(MAKE_DIRECTORY ${WORK_DIR})
set(capture ${WORK_DIR}/simulate_example2.pcapng)
execute_process(COMMAND ${TRIONET} ring simulate example2 --pcap ${capture} OUTPUT_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "trionet ring simulate example2 --pcap failed (${rc})")
endif()
execute_process(COMMAND ${TRIONET} ring decode --pcap ${capture} --json OUTPUT_FILE ${capture}.jsonl RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "trionet ring decode --pcap --json failed (${rc})")
endif()
execute_process(COMMAND ${PYTHON} ${SOURCE_DIR}/scripts/wireshark-compare --lua-dir ${SOURCE_DIR}/wireshark
                        ${capture} ${capture}.jsonl RESULT_VARIABLE rc)
if(rc EQUAL 77)
  message("SKIPPED: tshark is not installed")
elseif(NOT rc EQUAL 0)
  message(FATAL_ERROR "tshark shows the capture differently (${rc})")
endif()
