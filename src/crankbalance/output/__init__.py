"""Output edges: formatting of numbers and units for people (:mod:`.format`), figures, one
module per study (:mod:`.figures`), rendering to PNG, SVG, HTML and PDF (:mod:`.render`),
the building blocks of the HTML pages (:mod:`.html`), the balancing report
(:mod:`.report`) and the balance shop sheet (:mod:`.shop_sheet`)."""
