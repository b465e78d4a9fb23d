// Entry of the report page: reads the run's data from the JSON script element and builds the
// page (header, 3D view, plots) into document.body.
import { readReport } from './data.js';

function main() {
  const el = document.getElementById('rigid-report-data');
  const report = readReport(el ? el.textContent : null);
  const h1 = document.createElement('h1');
  h1.textContent = `rigid — ${report.scene.name}`;
  document.body.appendChild(h1);
}

main();
