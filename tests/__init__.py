"""Tests of tyrelab (a package: helpers import as ``tests.<module>``)."""
