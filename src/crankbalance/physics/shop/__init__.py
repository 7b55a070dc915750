"""The balance shop: from weighed parts and balancing-machine readings to a correction plan."""
