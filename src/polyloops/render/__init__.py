"""Pictures, drawn with matplotlib on its headless Agg backend."""
