# One task runner for people and CI alike (.ci/run calls `make test`).
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: demo test lint format bench clean browser dist

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -e '.[test]'
	touch $(STAMP)

## demo: install, then audit the bundled example icon set on the bundled theme
demo: $(STAMP)
	$(BIN)/alpha-audit check themes/github-primer.yaml examples/vibrant/iconset.yaml --alpha 1.1

## browser: Debian's chromium for the WebGL2 validation test (apt-get only when missing and root)
browser:
	@command -v chromium >/dev/null 2>&1 || [ -n "$$ALPHA_AUDIT_CHROMIUM" ] \
	  || { [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1 && apt-get update -qq \
	       && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null; } \
	  || echo "note: no chromium; the WebGL2 test needs it: sudo apt-get install -y chromium"

## dist: build the sdist and the wheel into dist/ and check their metadata
dist: $(STAMP)
	rm -rf dist
	$(BIN)/python -m build --quiet --outdir dist . >/dev/null
	$(BIN)/twine check --strict dist/*

## test: install, then lint, build and check the distributions, and run the whole test suite
test: $(STAMP) browser dist
	$(BIN)/ruff check src tests benchmarks tools
	$(BIN)/ruff format --check src tests benchmarks tools
	$(BIN)/pytest

lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks tools

format: $(STAMP)
	$(BIN)/ruff format src tests benchmarks tools
	$(BIN)/ruff check --fix src tests benchmarks tools

bench: $(STAMP)
	$(BIN)/python benchmarks/run.py

clean:
	rm -rf $(VENV) build dist src/*.egg-info .pytest_cache .hypothesis .ruff_cache
