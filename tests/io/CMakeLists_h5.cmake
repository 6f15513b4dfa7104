# Included from tests/io/CMakeLists.txt: tests of the HDF5 series writer and the JSON run summary
# (io/h5_series.*, io/summary_json.*). Serial tests (sec2 driver): no MPI launcher needed.
include(GoogleTest)
add_executable(raceway_io_h5_tests ${CMAKE_CURRENT_LIST_DIR}/h5_series_test.cpp ${CMAKE_CURRENT_LIST_DIR}/h5_writer_test.cpp)
target_link_libraries(raceway_io_h5_tests PRIVATE raceway::io GTest::gtest_main raceway_warnings)
gtest_discover_tests(raceway_io_h5_tests DISCOVERY_TIMEOUT 60 PROPERTIES LABELS "io")
