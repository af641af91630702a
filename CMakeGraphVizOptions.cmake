# What `make architecture` draws (cmake --graphviz reads this file from the source folder): the
# host library's modules (brdfcl_<folder>) and their links; not the CLI, the aggregate brdfcl_core,
# external libraries, tests, benchmarks or per-target files.
set(GRAPHVIZ_GRAPH_NAME "brdfcl")
set(GRAPHVIZ_EXTERNAL_LIBS FALSE)
set(GRAPHVIZ_GENERATE_PER_TARGET FALSE)
set(GRAPHVIZ_GENERATE_DEPENDERS FALSE)
set(GRAPHVIZ_CUSTOM_TARGETS FALSE)
set(GRAPHVIZ_IGNORE_TARGETS "^peer_" "^brdfcl_peers$" "^brdfcl-peers$" "^brdfcl-tests$" "^brdfcl-bench$"
    "^brdfcl_reference$" "^brdfcl_git_commit$" "^brdfcl_check_layers$" "^brdfcl$" "^brdfcl_core$")
