# Empties the smoke run's scratch corpus (cmake -DDIR=... -P reset_scratch.cmake), so every run
# of the suite, local or CI, starts from the committed seed corpus alone and takes the same path.
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
