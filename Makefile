# Two commands do all the set-up: `make demo` and `make test`.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
DOCS_STAMP := $(VENV)/.installed-docs

.PHONY: demo test lint bench mutants clean venv docs

venv: $(STAMP)

# pip's and setuptools' notices (the editable install's "Please be careful with folders" box)
# read as failures: a successful install is silent, a failed one prints its log
$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	@echo "installing dryfriction and its dependencies into $(VENV)/ (a few minutes; log: $(VENV)/pip.log)"
	@$(BIN)/python -m pip install -q --upgrade pip > $(VENV)/pip.log 2>&1 || { cat $(VENV)/pip.log; exit 1; }
	@$(BIN)/python -m pip install -q -e '.[test]' > $(VENV)/pip.log 2>&1 || { cat $(VENV)/pip.log; exit 1; }
	# compile the Numba kernels now (cached beside the sources), not in the user's first run
	$(BIN)/python -m dryfriction.warm
	touch $(STAMP)

demo: $(STAMP)
	$(BIN)/dryfriction reproduce --out results/
	@echo
	@echo "Open results/report.html in a browser (every figure and the key numbers)."
	@echo "The command line is $(BIN)/dryfriction (or: source $(BIN)/activate), e.g."
	@echo "  $(BIN)/dryfriction simulate examples/velocity_step.toml --out run/"
	@echo "  $(BIN)/dryfriction --help"

# the suite with the slow tests marked ci (one or more of each area: the README's commands, the
# site in a browser, huge runs refused, ...; pytest --co -q --slow-marked -m ci lists them), in
# one session; the other slow tests (each over ~3.5 s on 2 cores) run with: pytest --runslow
# the default suite on TEST_WORKERS processes (pytest-xdist; CI has 2 cores), a file per worker
# (--dist loadfile: a module's fixtures are computed once); TEST_WORKERS=0 runs it in one process
TEST_WORKERS ?= 2
test: $(STAMP)
	$(BIN)/python -m pytest -q -n $(TEST_WORKERS) --dist loadfile --with-ci

lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks

# the documentation site (API reference, gallery run from examples/gallery), offline, into
# docs/_build/html: open docs/_build/html/index.html
$(DOCS_STAMP): $(STAMP)
	@echo "installing the docs extra (Sphinx) into $(VENV)/ (log: $(VENV)/pip.log)"
	@$(BIN)/python -m pip install -q -e '.[test,docs]' > $(VENV)/pip.log 2>&1 || { cat $(VENV)/pip.log; exit 1; }
	touch $(DOCS_STAMP)

docs: $(DOCS_STAMP)
	rm -rf docs/_build docs/generated docs/auto_examples
	MPLBACKEND=Agg $(BIN)/python -m sphinx -q -W --keep-going -j auto -b html -d docs/_build/doctrees \
		docs docs/_build/html
	@echo "Open docs/_build/html/index.html in a browser."

bench: $(STAMP)
	$(BIN)/python -m benchmarks

# hand-written mutants against their tests (15-20 min on 2 cores before 2026-11-28, longer since
# their slow tests run too (--slow-marked): not measured since; not part of CI)
mutants: $(STAMP)
	$(BIN)/python -m tests.mutants

clean:
	rm -rf $(VENV) results build src/*.egg-info docs/_build docs/generated docs/auto_examples
