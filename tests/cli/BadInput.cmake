# Placeholder until the CLI lands; replaced by the bad-input cases.
