# The command reports (report/reports.hpp) in a real browser: the compare,
# diagnosis, identification and sweep reports of synthetic results, written
# by make_compare_report, are opened in headless Chromium (check_report.sh):
# no errors in the page, every plot drawn, screenshot not blank. Fails (does
# not skip) without chromium. Included from tests/CMakeLists.txt.
add_executable(make_compare_report ${CMAKE_CURRENT_LIST_DIR}/make_compare_report.cpp)
target_include_directories(make_compare_report PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})  # tests/: support/synthetic_reports.hpp
target_link_libraries(make_compare_report PRIVATE rigflex::report rigflex_warnings)
set(rigflex_command_report_dir ${CMAKE_CURRENT_BINARY_DIR}/browser)
# report kind and the plots it holds
foreach(kind_plots compare:23 diagnosis:14 identification:2 sweep:2)
  string(REPLACE ":" ";" kind_plots ${kind_plots})
  list(GET kind_plots 0 kind)
  list(GET kind_plots 1 plots)
  set(report ${rigflex_command_report_dir}/${kind}_command_report.html)
  add_test(NAME command_report_${kind}_write COMMAND make_compare_report ${kind} ${report})
  set_tests_properties(command_report_${kind}_write PROPERTIES FIXTURES_SETUP command_report_${kind})
  add_test(NAME command_report_${kind}_in_chromium
           COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/check_report.sh ${report} ${plots})
  set_tests_properties(command_report_${kind}_in_chromium PROPERTIES
    FIXTURES_REQUIRED command_report_${kind} TIMEOUT 600 LABELS browser)
endforeach()
