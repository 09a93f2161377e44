# dfc_warnings: the warning set every target of the project compiles with.
add_library(dfc_warnings INTERFACE)
target_compile_options(dfc_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion -Wnon-virtual-dtor
  -Wold-style-cast -Woverloaded-virtual -Wnull-dereference -Wdouble-promotion
  $<$<BOOL:${DFC_WARNINGS_AS_ERRORS}>:-Werror>)
