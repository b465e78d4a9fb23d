// Writes a small screenshot of a report page (the header's end, the 3D view and the first
// plot) for the docs: `node web/dev/screenshot.mjs PAGE.html OUT.png [TIME]`.
import { chromium } from '../node_modules/playwright-core/index.mjs';

const [page_, out, time] = process.argv.slice(2);
const browser = await chromium.launch({
  executablePath: '/usr/bin/chromium',
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
const page = await browser.newPage({ viewport: { width: 960, height: 820 } });
await page.goto(`file://${page_}`);
await page.evaluate(() => window.rigidReport.ready);
if (time) await page.evaluate((t) => window.rigidReport.setTime(Number(t)), time);
await page.evaluate(() => document.querySelector('.stage').scrollIntoView());
await page.waitForTimeout(300);
await page.screenshot({ path: out });
await browser.close();
