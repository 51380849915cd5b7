# System packages only (Debian); scripts/deps.sh installs them. No third-party source in the repo.
find_package(nlohmann_json 3.10 CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
if(SUPERMODAL_TESTS)
  find_package(GTest CONFIG REQUIRED)
endif()
if(SUPERMODAL_BENCH)
  find_package(benchmark CONFIG REQUIRED)
endif()
