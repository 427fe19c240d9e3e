# Two commands do all the set-up: `make demo` and `make test`.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: demo test lint bench mutants clean venv

venv: $(STAMP)

$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip
	$(BIN)/python -m pip install -q -e '.[test]'
	touch $(STAMP)

demo: $(STAMP)
	$(BIN)/dryfriction reproduce --out results/
	@echo
	@echo "Open results/report.html in a browser (every figure and the key numbers)."
	@echo "The command line is $(BIN)/dryfriction (or: source $(BIN)/activate), e.g."
	@echo "  $(BIN)/dryfriction simulate examples/velocity_step.toml --out run/"
	@echo "  $(BIN)/dryfriction --help"

# the suite, then the selected slow tests (each over ~20 s; all of them: pytest --runslow)
SLOW_SUBSET := ageing_under_load or huge_run_sizes
test: $(STAMP)
	$(BIN)/python -m pytest -q
	$(BIN)/python -m pytest -q --runslow -m slow -k "$(SLOW_SUBSET)"

lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks

bench: $(STAMP)
	$(BIN)/python -m benchmarks

# hand-written mutants against their tests (about 15-20 min on 2 cores; not part of CI)
mutants: $(STAMP)
	$(BIN)/python -m tests.mutants

clean:
	rm -rf $(VENV) results build src/*.egg-info
