# The two set-up commands of the README: `make demo` and `make test`. Both install what is
# missing, configure and build into build/ and run.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all deps configure build demo test sanitize bench docs clean

all: build

deps:
	@bash scripts/install-deps.sh

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)

configure: deps $(BUILD)/CMakeCache.txt

build: configure
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	@bash scripts/demo.sh $(BUILD)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# Without PETSc (-DPACKLAB_PETSC=OFF): the build a user without it gets, checked here; MPI under
# the sanitizers would also report Open MPI's own leaks.
# AddressSanitizer + UndefinedBehaviorSanitizer (CMake option PACKLAB_SANITIZE): the library,
# the command line and the tests built into build-sanitize/ (no Python module, no benchmarks),
# then the tests run there. Any finding stops that test with the report. SANITIZE_DIRS picks
# a sample: the tests whose suites are defined under those tests/ folders, e.g.
#   make sanitize SANITIZE_DIRS="core io dem"
SANITIZE_BUILD ?= build-sanitize
SANITIZE_DIRS ?=
PAREN := (
SANITIZE_SUITES = $(shell grep -rhoE '^TEST(_F|_P)?[$(PAREN)][A-Za-z0-9_]+' $(addprefix tests/,$(SANITIZE_DIRS)) \
                          | sed 's/.*[$(PAREN)]//' | sort -u | paste -sd'|')
# Stack traces for UBSan findings too; ASan's defaults plus the initialization-order checks.
ASAN_OPTIONS ?= check_initialization_order=1:strict_init_order=1
UBSAN_OPTIONS ?= print_stacktrace=1

$(SANITIZE_BUILD)/CMakeCache.txt:
	cmake -S . -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=Release -DPACKLAB_SANITIZE=ON -DPACKLAB_BENCH=OFF -DPACKLAB_PETSC=OFF $(CMAKE_FLAGS)

sanitize: deps $(SANITIZE_BUILD)/CMakeCache.txt
	cmake --build $(SANITIZE_BUILD) -j $(JOBS) --target packlab_tests
	cd $(SANITIZE_BUILD) && ASAN_OPTIONS=$(ASAN_OPTIONS) UBSAN_OPTIONS=$(UBSAN_OPTIONS) ctest --output-on-failure -j $(JOBS) $(if $(SANITIZE_DIRS),-R '(^|/)($(SANITIZE_SUITES))\.')

bench: build
	@bash bench/run.sh $(BUILD)

docs: build
	@bash scripts/make-docs.sh $(BUILD)

clean:
	rm -rf $(BUILD)
