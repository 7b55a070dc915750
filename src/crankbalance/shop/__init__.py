"""The balance shop: from weighed parts to a drilling plan for any crank (issue 16)."""
