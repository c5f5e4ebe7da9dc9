# Test files compiled on their own in a unity build (cmake/BuildSpeed.cmake): their file-local
# helpers (runGblens, write, kFrame, ...) share names with another test file's of the same executable.
set(GBLENS_UNITY_ALONE
    cli/test_cli.cpp cli/test_cli_accuracy.cpp cli/test_compare_flip.cpp cli/test_compare_formats.cpp
    cli/test_compare_masks.cpp cli/test_foreign_suggest.cpp cli/test_suggest.cpp cli/test_renderdoc.cpp
    cli/test_foreign.cpp)
