# Sable build. `make` builds bin/sable and build/libsable.a (the tests link it).
#   make DEBUG=1      debug build (-O0 -g, PetscAssert active), all in build-debug/ (its
#                     binary build-debug/bin/sable; bin/sable stays the optimised one)
#   make check        installs missing packages, builds, runs the quick tier (tests/check.list)
#   make test         installs missing packages, builds, runs the whole suite
#   make run          installs missing packages, builds, runs the default case
#   make bench        the performance benchmarks (never part of `make test`)
DEBUG ?= 0
ifeq ($(DEBUG),1)
  BUILD ?= build-debug
  BIN ?= build-debug/bin
  OPT = -O0 -g -DSABLE_DEBUG
else
  BUILD ?= build
  OPT = -O3 -march=native -fno-math-errno -DNDEBUG
endif
BIN ?= bin
CC = mpicc
PKGS = petsc ccd hdf5-openmpi
# -MMD -MP: the compiler writes each object's header dependencies beside it (%.d, read below),
# so a header edit rebuilds only the objects and tests that include it.
DEPFLAGS = -MMD -MP
CFLAGS = -std=c11 -D_POSIX_C_SOURCE=200809L -Wall -Wextra $(OPT) $(DEPFLAGS) \
         $(shell pkg-config --cflags $(PKGS) 2>/dev/null) -Isrc
LDLIBS = $(shell pkg-config --libs $(PKGS) 2>/dev/null) -lm

LIB_SRC = $(filter-out src/main.c,$(shell find src -name '*.c' | sort))
LIB_OBJ = $(LIB_SRC:%.c=$(BUILD)/%.o)
# Tests: tests/<folder>/test_*.c -> $(BUILD)/tests/<folder>/test_*; tests/common/ holds the
# shared harness headers (on the tests' include path); TEST_DIR tells a test its own folder,
# where its scenes (*.opts) are.
TEST_SRC = $(wildcard tests/*/*.c)
TEST_BIN = $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)

.PHONY: all deps check test run bench validate clean
all: $(BIN)/sable $(TEST_BIN) $(BUILD)/tools/tradeoff_run $(BUILD)/tools/umf_sweep $(BUILD)/tools/grid_settle

deps:
	@tools/install-deps.sh

# The option names written in src/ (tools/gen-options.sh); rewritten only when they change, so
# that sable.c, which includes it, is rebuilt only then.
$(BUILD)/gen/sable_options.h: $(LIB_SRC) src/main.c tools/gen-options.sh
	@mkdir -p $(dir $@)
	@tools/gen-options.sh src > $@.tmp
	@if cmp -s $@.tmp $@; then rm -f $@.tmp; else mv $@.tmp $@; fi

$(BUILD)/src/sable.o: $(BUILD)/gen/sable_options.h
$(BUILD)/src/sable.o: CFLAGS += -I$(BUILD)/gen

# An object whose %.d is missing (built before, or by a Makefile without it) is rebuilt, since
# nothing then says which headers it saw.
$(BUILD)/%.o: %.c $(BUILD)/%.d
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -c $< -o $@
$(BUILD)/%.d: ;
.PRECIOUS: $(BUILD)/%.d

$(BUILD)/libsable.a: $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(BIN)/sable: $(BUILD)/src/main.o $(BUILD)/libsable.a
	@mkdir -p $(BIN)
	$(CC) $(CFLAGS) $^ $(LDLIBS) -o $@

$(BUILD)/tests/%: tests/%.c $(BUILD)/libsable.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -MF $@.d -MT $@ -Itests/common -DTEST_DIR='"$(abspath $(dir $<))"' $< $(BUILD)/libsable.a $(LDLIBS) -o $@

# The targets that a fresh machine runs first install what is missing, then build, on every
# core unless make was given -j itself.
JOBS = $(if $(findstring j,$(firstword $(MAKEFLAGS)))$(findstring jobserver,$(MAKEFLAGS)),,-j$(shell nproc 2>/dev/null || echo 1))
# `make check` is the quick tier a kernel change runs first (the tests named in tests/check.list);
# `make test` the whole suite.
check: deps
	@$(MAKE) --no-print-directory -s $(JOBS) $(BIN)/sable $(TEST_BIN)
	@BUILD=$(BUILD) BIN=$(BIN) TIER=check tests/run.sh

test: deps
	@$(MAKE) --no-print-directory -s $(JOBS) all
	@BUILD=$(BUILD) BIN=$(BIN) tests/run.sh

run: deps
	@$(MAKE) --no-print-directory -s $(JOBS) all
	tools/run-default.sh

bench: deps
	@$(MAKE) --no-print-directory -s $(JOBS) all
	tools/bench.sh

validate: deps
	@$(MAKE) --no-print-directory -s $(JOBS) all
	tools/validate.sh

clean:
	rm -rf build build-debug bin

# Stand-alone tools, not part of `all`: e.g. make build/tools/bench_convex
$(BUILD)/tools/%: tools/%.c $(BUILD)/libsable.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -MF $@.d -MT $@ $< $(BUILD)/libsable.a $(LDLIBS) -o $@

# The header dependencies the compiler wrote (none before the first build, when every object is
# built anyway; the generated sable_options.h is named above for that first build).
-include $(LIB_OBJ:.o=.d) $(BUILD)/src/main.d $(TEST_BIN:=.d) $(wildcard $(BUILD)/tools/*.d)
