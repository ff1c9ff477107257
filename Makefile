# Sable build. `make` builds bin/sable and build/libsable.a (the tests link it).
#   make DEBUG=1      debug build (-O0 -g, PetscAssert active), all in build-debug/ (its
#                     binary build-debug/bin/sable; bin/sable stays the optimised one)
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
CFLAGS = -std=c11 -D_POSIX_C_SOURCE=200809L -Wall -Wextra $(OPT) \
         $(shell pkg-config --cflags $(PKGS) 2>/dev/null) -Isrc
LDLIBS = $(shell pkg-config --libs $(PKGS) 2>/dev/null) -lm

LIB_SRC = $(filter-out src/main.c,$(shell find src -name '*.c' | sort))
LIB_OBJ = $(LIB_SRC:%.c=$(BUILD)/%.o)
# Tests: tests/<folder>/test_*.c -> $(BUILD)/tests/<folder>/test_*; tests/common/ holds the
# shared harness headers (on the tests' include path); TEST_DIR tells a test its own folder,
# where its scenes (*.opts) are.
TEST_SRC = $(wildcard tests/*/*.c)
TEST_BIN = $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)
TEST_HDRS = $(wildcard tests/common/*.h)
HDRS = $(shell find src -name '*.h')

.PHONY: all deps test run bench clean
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

$(BUILD)/%.o: %.c $(HDRS)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -c $< -o $@

$(BUILD)/libsable.a: $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(BIN)/sable: $(BUILD)/src/main.o $(BUILD)/libsable.a
	@mkdir -p $(BIN)
	$(CC) $(CFLAGS) $^ $(LDLIBS) -o $@

$(BUILD)/tests/%: tests/%.c $(BUILD)/libsable.a $(HDRS) $(TEST_HDRS)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -Itests/common -DTEST_DIR='"$(abspath $(dir $<))"' $< $(BUILD)/libsable.a $(LDLIBS) -o $@

# The targets that a fresh machine runs first install what is missing, then build.
test: deps
	@$(MAKE) --no-print-directory -s all
	@BUILD=$(BUILD) BIN=$(BIN) tests/run.sh

run: deps
	@$(MAKE) --no-print-directory -s all
	tools/run-default.sh

bench: deps
	@$(MAKE) --no-print-directory -s all
	tools/bench.sh

clean:
	rm -rf build build-debug bin

# Stand-alone tools, not part of `all`: e.g. make build/tools/bench_convex
$(BUILD)/tools/%: tools/%.c $(BUILD)/libsable.a $(HDRS)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) $< $(BUILD)/libsable.a $(LDLIBS) -o $@
