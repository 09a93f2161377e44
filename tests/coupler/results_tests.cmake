# Results output tests (ResultsWriter, XDMF sidecar, plot tool). Included from
# tests/coupler/CMakeLists.txt; needs the dfc_coupler library (results_writer.cpp,
# xdmf_writer.cpp) and GoogleTest (include(GoogleTest) is done in tests/).
add_executable(results_tests
  ${CMAKE_CURRENT_LIST_DIR}/results_writer_tests.cpp
  ${CMAKE_CURRENT_LIST_DIR}/results_xdmf_tests.cpp
)
target_include_directories(results_tests PRIVATE ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(results_tests PRIVATE dfc_coupler GTest::gtest_main dfc_warnings)
gtest_discover_tests(results_tests PROPERTIES LABELS unit)

# A small pile-run-shaped results file for the checks that run outside C++.
add_executable(results_sample ${CMAKE_CURRENT_LIST_DIR}/results_sample_main.cpp)
target_include_directories(results_sample PRIVATE ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(results_sample PRIVATE dfc_coupler dfc_warnings)

set(DFC_RESULTS_SAMPLE_DIR ${CMAKE_CURRENT_BINARY_DIR}/results_sample)
add_test(NAME results.sample_file COMMAND results_sample ${DFC_RESULTS_SAMPLE_DIR}/sample.h5)
set_tests_properties(results.sample_file PROPERTIES LABELS unit FIXTURES_SETUP dfc_results_sample)

# The Debian python first: python3-h5py/-matplotlib are installed for it, and a
# python3 earlier on PATH (pyenv, venv) may lack them.
find_program(DFC_PYTHON3 NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
find_program(DFC_PYTHON3 NAMES python3)
if(DFC_PYTHON3)
  # A real XML parser on the sidecar ParaView will read.
  add_test(NAME results.xdmf_parses_as_xml
    COMMAND ${DFC_PYTHON3} -c "import sys, xml.dom.minidom; d = xml.dom.minidom.parse(sys.argv[1]); assert d.documentElement.tagName == 'Xdmf'"
            ${DFC_RESULTS_SAMPLE_DIR}/sample.xdmf)
  set_tests_properties(results.xdmf_parses_as_xml PROPERTIES LABELS unit FIXTURES_REQUIRED dfc_results_sample)

  # The plot tool on the sample; exit code 77 (skipped) when h5py or matplotlib are missing.
  add_test(NAME results.plot_tool
    COMMAND ${DFC_PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/results_plot_check.py
            ${CMAKE_CURRENT_LIST_DIR}/../../tools/plot_results.py ${DFC_RESULTS_SAMPLE_DIR}/sample.h5 ${DFC_RESULTS_SAMPLE_DIR}/plots)
  set_tests_properties(results.plot_tool PROPERTIES LABELS unit FIXTURES_REQUIRED dfc_results_sample SKIP_RETURN_CODE 77)
else()
  message(STATUS "python3 not found: the XDMF parse and plot-tool tests are not registered")
endif()
