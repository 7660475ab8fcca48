"""What several nodes share: start-up, signals, the readers, the drive loop, parameters, tf."""
